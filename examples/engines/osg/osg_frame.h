// The OpenSceneGraph programs' shared frame helpers (decal_osg.cpp, edges_osg.cpp): one frame
// read back the engine's way, and the depth buffer's bits read inside OSG's own framebuffer.
#ifndef ZSHIFT_EXAMPLES_OSG_FRAME_H
#define ZSHIFT_EXAMPLES_OSG_FRAME_H

#include <osg/Drawable>
#include <osg/GL>
#include <osg/Image>
#include <osgDB/WriteFile>
#include <osgViewer/Viewer>

#include <iostream>
#include <string>

#include "../common/decal_scene.h"

// Renders one frame and reads it back the engine's way: OSG copies the camera's colour
// attachment into the attached osg::Image after drawing. Saves it as `png` when non-empty.
static bool shoot(osgViewer::Viewer &viewer, osg::Image &image, decal_scene::Picture &out,
                  const std::string &png) {
  viewer.frame();
  out.width = image.s();
  out.height = image.t();
  const unsigned char *data = image.data();
  if (!data || image.getPixelFormat() != GL_RGBA || image.getDataType() != GL_UNSIGNED_BYTE) {
    std::cerr << "FAIL: OpenSceneGraph read no RGBA8 picture back\n";
    return false;
  }
  out.rgba.assign(data, data + (size_t)4 * out.width * out.height);
  if (!png.empty() && !osgDB::writeImageFile(image, png)) {
    std::cerr << "FAIL: could not write " << png << "\n";
    return false;
  }
  return true;
}

// Reads GL_DEPTH_BITS while a drawable draws, so inside the camera's framebuffer object.
struct DepthBits : osg::Drawable::DrawCallback {
  mutable GLint bits = 0, subpixel_bits = 0;
  mutable std::string renderer;
  void drawImplementation(osg::RenderInfo &info, const osg::Drawable *drawable) const override {
    renderer = (const char *)glGetString(GL_RENDERER);
    glGetIntegerv(GL_DEPTH_BITS, &bits);
    glGetIntegerv(GL_SUBPIXEL_BITS, &subpixel_bits);
    drawable->drawImplementation(info);
  }
};

#endif
