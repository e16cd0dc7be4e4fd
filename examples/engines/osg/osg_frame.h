// The OpenSceneGraph programs' shared frame helpers (decal_osg.cpp, edges_osg.cpp): the window,
// the camera rendering into a framebuffer object, one frame read back the engine's way, and the
// depth buffer's bits read inside OSG's own framebuffer.
#ifndef ZSHIFT_EXAMPLES_OSG_FRAME_H
#define ZSHIFT_EXAMPLES_OSG_FRAME_H

#include <osg/Drawable>
#include <osg/GL>
#include <osg/Camera>
#include <osg/GraphicsContext>
#include <osg/Image>
#include <osg/Viewport>
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

// The window OSG draws from, kWidth x kHeight on the X display of $DISPLAY (Mesa's pbuffers raise
// X errors under Xvfb; the frame itself goes to the camera's framebuffer object); null, with the
// reason on stderr, where none can be made.
static osg::ref_ptr<osg::GraphicsContext> open_window() {
  using decal_scene::kHeight;
  using decal_scene::kWidth;
  osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
  traits->readDISPLAY(); // the X display and screen from $DISPLAY
  traits->setUndefinedScreenDetailsToDefaultScreen();
  traits->width = kWidth;
  traits->height = kHeight;
  traits->red = traits->green = traits->blue = traits->alpha = 8;
  traits->depth = 24;
  traits->doubleBuffer = true;
  traits->windowDecoration = false;
  osg::ref_ptr<osg::GraphicsContext> gc = osg::GraphicsContext::createGraphicsContext(traits.get());
  if (!gc.valid()) {
    std::cerr << "FAIL: OpenSceneGraph could not create a " << kWidth << "x" << kHeight
              << " window on display " << traits->displayName() << "\n";
  }
  return gc;
}

// The viewer's camera on `gc`: single-threaded, the whole window, cleared to black.
static osg::Camera *window_camera(osgViewer::Viewer &viewer, osg::GraphicsContext *gc) {
  viewer.setThreadingModel(osgViewer::ViewerBase::SingleThreaded);
  osg::Camera *camera = viewer.getCamera();
  camera->setGraphicsContext(gc);
  camera->setViewport(new osg::Viewport(0, 0, decal_scene::kWidth, decal_scene::kHeight));
  camera->setClearColor(osg::Vec4(0, 0, 0, 1));
  return camera;
}

// Renders the camera into a framebuffer object with exactly the depth format asked for (a window
// system picks its own: Mesa's GLX on Xvfb gives 32 bits); OSG reads the colour back into the
// returned image after each frame.
static osg::ref_ptr<osg::Image> render_to_image(osg::Camera *camera, GLenum depth_format) {
  osg::ref_ptr<osg::Image> image = new osg::Image;
  image->allocateImage(decal_scene::kWidth, decal_scene::kHeight, 1, GL_RGBA, GL_UNSIGNED_BYTE);
  camera->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT, osg::Camera::FRAME_BUFFER);
  camera->attach(osg::Camera::DEPTH_BUFFER, depth_format);
  camera->attach(osg::Camera::COLOR_BUFFER, image.get());
  return image;
}

#endif
