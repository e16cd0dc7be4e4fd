// An Ogre 1.12 program drawing a decal with zshift's projection.
//
// Two viewports share one render window: the first, cleared, shows the ground and the occluder
// through the main camera; the second, not cleared and drawn after it, shows only the decal
// through a camera at the same place whose custom projection matrix is zshift's decal matrix,
// built from the main camera's. For each view of the scene (README, "Inside real engines") the
// program renders with no offset and with zshift's matrix, reads every frame back with
// RenderTarget::copyContentsToMemory, saves the pictures and exits nonzero unless the decal
// z-fights without an offset and loses no pixel (and bleeds through no occluder beyond
// zshift's bleed gap) with zshift's.
//
// Usage: decal_ogre [--subpixel-bits B] [OUTPUT_DIR]   (Ogre's OpenGL render system opens an
// X11 window: run it under xvfb-run)
#include <Ogre.h>

#include <GL/gl.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "zshift.h"

#include "../common/decal_scene.h"

using namespace decal_scene;

// [quickstart-engines-ogre]
// zshift inside Ogre: the decal camera's projection, from the main camera's own (OpenGL render
// system): only element 10 changes, by just enough to beat the rasterizer's rounding for
// `decal`. Give it to a second camera at the same place:
// decal_camera->setCustomProjectionMatrix(true, decal_projection).
static bool zshift_decal_projection(const Ogre::Camera &camera, const ZshiftDecal &decal,
                                    Ogre::Matrix4 &decal_projection) {
  float m[16], out[16]; // column-major; Ogre::Matrix4 is row-major
  const Ogre::Matrix4 &p = camera.getProjectionMatrix();
  for (int i = 0; i < 16; i++) m[i] = p[i % 4][i / 4];
  if (zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out) != ZSHIFT_OK) {
    std::fprintf(stderr, "zshift_decal_matrix: %s\n", zshift_last_error());
    return false;
  }
  decal_projection = Ogre::Matrix4(out).transpose();
  return true;
}
// [/quickstart-engines-ogre]

// A rectangle (tiled when tile > 0) of one colour, unlit.
static Ogre::ManualObject *rectangle(Ogre::SceneManager *sm, const char *name, const Rect &r,
                                     double tile, const Ogre::ColourValue &colour) {
  std::vector<float> xyz = triangles(r, tile, 1.0);
  Ogre::ManualObject *obj = sm->createManualObject(name);
  obj->begin("zshift/unlit", Ogre::RenderOperation::OT_TRIANGLE_LIST);
  for (size_t i = 0; i < xyz.size(); i += 3) {
    obj->position(xyz[i], xyz[i + 1], xyz[i + 2]);
    obj->colour(colour);
  }
  obj->end();
  obj->setCastShadows(false);
  sm->getRootSceneNode()->createChildSceneNode()->attachObject(obj);
  return obj;
}

static bool shoot(Ogre::Root &root, Ogre::RenderWindow *window, Picture &out,
                  const std::string &png) {
  root.renderOneFrame();
  out.width = (int)window->getWidth();
  out.height = (int)window->getHeight();
  out.rgba.assign((size_t)4 * out.width * out.height, 0);
  // Ogre's PF_BYTE_RGBA is R, G, B, A in memory; rows come top-down.
  std::vector<unsigned char> top_down(out.rgba.size());
  Ogre::PixelBox box(out.width, out.height, 1, Ogre::PF_BYTE_RGBA, top_down.data());
  window->copyContentsToMemory(Ogre::Box(0, 0, out.width, out.height), box,
                               Ogre::RenderTarget::FB_BACK);
  for (int y = 0; y < out.height; y++)
    std::copy_n(&top_down[(size_t)4 * out.width * (out.height - 1 - y)], 4 * out.width,
                &out.rgba[(size_t)4 * out.width * y]);
  if (!png.empty()) window->writeContentsToFile(png);
  return true;
}

int main(int argc, char **argv) {
  Options options;
  if (!parse_options(argc, argv, options)) return 1;
  if (options.reversed) {
    std::fprintf(stderr, "FAIL: --reversed: this example uses Ogre's OpenGL render system, which "
                         "has no reversed-Z setup\n");
    return 1;
  }

  try {
    Ogre::LogManager *logs = new Ogre::LogManager;
    logs->createLog("", true, false, true); // default log, not written to a file or stdout
    Ogre::Root root("", "", "");
    root.loadPlugin(OGRE_PLUGIN_DIR "/RenderSystem_GL");
    root.loadPlugin(OGRE_PLUGIN_DIR "/Codec_STBI"); // writes the PNG pictures
    Ogre::RenderSystem *rs = root.getRenderSystemByName("OpenGL Rendering Subsystem");
    if (!rs) {
      std::fprintf(stderr, "FAIL: Ogre has no OpenGL render system\n");
      return 1;
    }
    root.setRenderSystem(rs);
    root.initialise(false);
    Ogre::NameValuePairList params;
    params["FSAA"] = "0";
    params["vsync"] = "false";
    Ogre::RenderWindow *window = root.createRenderWindow("zshift decal", kWidth, kHeight, false, &params);
    window->setAutoUpdated(true);

    GLint depth_bits = 0, subpixel_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    glGetIntegerv(GL_SUBPIXEL_BITS, &subpixel_bits);
    std::printf("Ogre %d.%d.%d on %s; depth bits %d, subpixel bits %d\n", OGRE_VERSION_MAJOR,
                OGRE_VERSION_MINOR, OGRE_VERSION_PATCH, (const char *)glGetString(GL_RENDERER),
                depth_bits, subpixel_bits);
    if (options.subpixel_bits != kAskGL) subpixel_bits = options.subpixel_bits;
    if (!known_depth_bits(depth_bits)) return 1;

    Ogre::ResourceGroupManager::getSingleton().initialiseAllResourceGroups();
    Ogre::MaterialPtr unlit = Ogre::MaterialManager::getSingleton().create(
        "zshift/unlit", Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
    Ogre::Pass *pass = unlit->getTechnique(0)->getPass(0);
    pass->setLightingEnabled(false);
    pass->setCullingMode(Ogre::CULL_NONE);

    Ogre::SceneManager *sm = root.createSceneManager();
    const Ogre::uint32 kBase = 1, kDecalMask = 2;
    const Ogre::ColourValue blue(0, 0, 1);
    Ogre::ManualObject *ground = rectangle(sm, "ground", kGround, 0.0, blue);
    Ogre::ManualObject *tiles = rectangle(sm, "tiles", kGround, kViews[1].ground_tile, blue);
    Ogre::ManualObject *occluder = rectangle(sm, "occluder", kOccluder, 0.0, Ogre::ColourValue(1, 1, 0));
    Ogre::ManualObject *decal = rectangle(sm, "decal", kDecal, 0.0, Ogre::ColourValue(1, 0, 0));
    ground->setVisibilityFlags(kBase);
    tiles->setVisibilityFlags(kBase);
    occluder->setVisibilityFlags(kBase);
    decal->setVisibilityFlags(kDecalMask);

    Ogre::Camera *camera = sm->createCamera("main");
    camera->setFOVy(Ogre::Degree((Ogre::Real)kFovyDegrees));
    camera->setAspectRatio((Ogre::Real)kWidth / kHeight);
    camera->setNearClipDistance((Ogre::Real)kNear);
    camera->setFarClipDistance((Ogre::Real)kFar);
    Ogre::SceneNode *eye = sm->getRootSceneNode()->createChildSceneNode();
    eye->attachObject(camera);
    Ogre::Camera *decal_camera = sm->createCamera("decal");
    decal_camera->setFOVy(camera->getFOVy());
    decal_camera->setAspectRatio(camera->getAspectRatio());
    decal_camera->setNearClipDistance(camera->getNearClipDistance());
    decal_camera->setFarClipDistance(camera->getFarClipDistance());
    eye->attachObject(decal_camera);

    // [quickstart-engines-ogre-viewports]
    // The base through the main camera; then the decal alone, over it, through the decal camera
    // (same place, zshift's projection), keeping the base's depth.
    Ogre::Viewport *base_vp = window->addViewport(camera, 0);
    base_vp->setVisibilityMask(kBase);
    Ogre::Viewport *decal_vp = window->addViewport(decal_camera, 1);
    decal_vp->setVisibilityMask(kDecalMask);
    decal_vp->setClearEveryFrame(false);
    // [/quickstart-engines-ogre-viewports]
    base_vp->setBackgroundColour(Ogre::ColourValue(0, 0, 0, 1));
    base_vp->setOverlaysEnabled(false);
    decal_vp->setOverlaysEnabled(false);

    const Ogre::Matrix4 projection = camera->getProjectionMatrix();
    Ogre::Matrix4 zshift_projection, over_projection;
    Engine engine;
    engine.depth_test = "GL_LEQUAL"; // Ogre's default depth function, CMPF_LESS_EQUAL
    engine.show_base = [&](bool on) { base_vp->setVisibilityMask(on ? kBase : 0); };
    engine.show_decal = [&](bool on) { decal_vp->setVisibilityMask(on ? kDecalMask : 0); };
    engine.decal_projection = [&](Method m) {
      decal_camera->setCustomProjectionMatrix(
          true, m == kNoOffset ? projection : m == kZshift ? zshift_projection : over_projection);
    };
    engine.shoot = [&](Picture &out, const std::string &png) { return shoot(root, window, out, png); };

    int failed = 0;
    for (const View &view : kViews) {
      ground->setVisible(view.ground_tile == 0.0);
      tiles->setVisible(view.ground_tile != 0.0);
      Axes a = axes(view);
      auto vec = [](const double v[3]) { return Ogre::Vector3((Ogre::Real)v[0], (Ogre::Real)v[1], (Ogre::Real)v[2]); };
      const double back[3] = {-a.forward[0], -a.forward[1], -a.forward[2]}; // Ogre cameras look down -z
      eye->setPosition(vec(view.eye));
      eye->setOrientation(Ogre::Quaternion(vec(a.right), vec(a.up), vec(back)));
      engine.name = "Ogre D" + std::to_string(depth_bits) + " " + view.name;
      std::printf("%s: ", engine.name.c_str());

      // What the engine knows about its decal, from the camera's view matrix.
      Ogre::Affine3 v = camera->getViewMatrix();
      double view_matrix[16];
      for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) view_matrix[4 * col + row] = row < 3 ? v[row][col] : (col == 3);
      float decal_corners[4][3];
      corners(kDecal, 1.0, decal_corners);
      DecalExtent ext = decal_extent(view_matrix, decal_corners, -1.0);
      ZshiftDecal decal_info =
          describe_decal(unorm_format(depth_bits), subpixel_bits, ext, ground_reach(view_matrix, 1.0, view));
      if (!zshift_decal_projection(*camera, decal_info, zshift_projection)) return 1;
      float m[16], z[16], over[16];
      for (int i = 0; i < 16; i++) {
        m[i] = projection[i % 4][i / 4];
        z[i] = zshift_projection[i % 4][i / 4];
      }
      print_changed(m, z);
      engine.bleed_gap = bleed_gap(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, decal_info);
      engine.occluder_gap = occluder_gap(view);
      if (!control_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, engine.occluder_gap, ext, over)) return 1;
      over_projection = Ogre::Matrix4(over).transpose();
      failed |= compare(engine, options.out_dir,
                        "ogre_d" + std::to_string(depth_bits) + "_" + view.name + "_");
    }
    return failed;
  } catch (const Ogre::Exception &e) {
    std::fprintf(stderr, "FAIL: Ogre: %s\n", e.getFullDescription().c_str());
    return 1;
  }
}
