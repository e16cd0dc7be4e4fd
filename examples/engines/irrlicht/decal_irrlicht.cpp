// An Irrlicht 1.8 program drawing a decal with zshift's projection.
//
// The scene manager draws the ground and the occluder with the camera's own projection; the
// decal pass sets zshift's decal matrix with IVideoDriver::setTransform(ETS_PROJECTION, ...)
// and draws the decal. For each view of the scene (README, "Inside real engines") the program
// renders with no offset and with zshift's matrix, reads every frame back with
// IVideoDriver::createScreenShot, saves the pictures and exits nonzero unless the decal
// z-fights without an offset and loses no pixel (and bleeds through no occluder beyond zshift's
// bleed gap) with zshift's.
//
// Usage: decal_irrlicht [--subpixel-bits B] [OUTPUT_DIR]   (Irrlicht opens an X11 window: run
// it under xvfb-run)
#include <irrlicht.h>

#include <GL/gl.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "zshift.h"

#include "../common/decal_scene.h"

using namespace irr;
using namespace decal_scene;

// [quickstart-engines-irrlicht]
// zshift inside Irrlicht: the decal pass's projection, from the camera's own. Irrlicht's OpenGL
// driver loads the camera's Direct3D-style left-handed matrix as it is (w = +z, depth in
// [0, 1]); under OpenGL's [-1, 1] clip that is a frustum whose near plane lies at nf/(2f - n),
// and zshift reads it so from the matrix. Only element 10 changes.
static bool zshift_decal_projection(const scene::ICameraSceneNode &camera, const ZshiftDecal &decal,
                                    core::matrix4 &decal_projection) {
  float out[16]; // column-major: irr::core::matrix4's memory order too
  const float *m = camera.getProjectionMatrix().pointer();
  if (zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out) != ZSHIFT_OK) {
    std::fprintf(stderr, "zshift_decal_matrix: %s\n", zshift_last_error());
    return false;
  }
  decal_projection.setM(out);
  return true;
}
// [/quickstart-engines-irrlicht]

// A rectangle (tiled when tile > 0) as a mesh buffer of one colour, z mirrored: Irrlicht's
// world is left-handed.
static void fill(scene::SMeshBuffer &buffer, const Rect &r, double tile, video::SColor color) {
  std::vector<float> xyz = triangles(r, tile, -1.0);
  buffer.Vertices.clear();
  buffer.Indices.clear();
  for (size_t i = 0; i < xyz.size(); i += 3) {
    buffer.Vertices.push_back(video::S3DVertex(xyz[i], xyz[i + 1], xyz[i + 2], 0, 1, 0, color, 0, 0));
    buffer.Indices.push_back((u16)(i / 3));
  }
  buffer.Material.Lighting = false;
  buffer.Material.BackfaceCulling = false;
  buffer.recalculateBoundingBox();
}

static scene::IMeshSceneNode *add_rectangle(scene::ISceneManager *smgr, const Rect &r, double tile,
                                            video::SColor color) {
  scene::SMeshBuffer *buffer = new scene::SMeshBuffer;
  fill(*buffer, r, tile, color);
  scene::SMesh *mesh = new scene::SMesh;
  mesh->addMeshBuffer(buffer);
  mesh->recalculateBoundingBox();
  buffer->drop();
  scene::IMeshSceneNode *node = smgr->addMeshSceneNode(mesh);
  mesh->drop();
  node->setAutomaticCulling(scene::EAC_OFF);
  return node;
}

struct Frame {
  IrrlichtDevice *device;
  scene::ICameraSceneNode *camera;
  scene::SMeshBuffer *decal;
  const core::matrix4 *decal_projection;
  bool decal_shown;

  // Draws one frame (scene manager, then the decal pass) and reads it back with the engine's
  // screenshot; saves it as `png` when non-empty.
  bool shoot(Picture &out, const std::string &png) {
    video::IVideoDriver *driver = device->getVideoDriver();
    device->run();
    driver->beginScene(true, true, video::SColor(255, 0, 0, 0));
    device->getSceneManager()->drawAll();
    if (decal_shown) {
      // [quickstart-engines-irrlicht-pass]
      // The decal pass, after smgr->drawAll(): zshift's projection, the camera's view.
      driver->setTransform(video::ETS_PROJECTION, *decal_projection);
      driver->setTransform(video::ETS_VIEW, camera->getViewMatrix());
      driver->setTransform(video::ETS_WORLD, core::IdentityMatrix);
      driver->setMaterial(decal->Material);
      driver->drawMeshBuffer(decal);
      // [/quickstart-engines-irrlicht-pass]
    }
    driver->endScene();
    video::IImage *shot = driver->createScreenShot();
    if (!shot) {
      std::fprintf(stderr, "FAIL: IVideoDriver::createScreenShot returned no image\n");
      return false;
    }
    core::dimension2du size = shot->getDimension();
    out.width = (int)size.Width;
    out.height = (int)size.Height;
    out.rgba.assign((size_t)4 * out.width * out.height, 0);
    for (int y = 0; y < out.height; y++) {
      for (int x = 0; x < out.width; x++) {
        video::SColor c = shot->getPixel(x, out.height - 1 - y); // top-down -> bottom-up
        unsigned char *p = &out.rgba[4 * ((size_t)y * out.width + x)];
        p[0] = (unsigned char)c.getRed();
        p[1] = (unsigned char)c.getGreen();
        p[2] = (unsigned char)c.getBlue();
        p[3] = (unsigned char)c.getAlpha();
      }
    }
    bool ok = png.empty() || driver->writeImageToFile(shot, png.c_str());
    shot->drop();
    if (!ok) std::fprintf(stderr, "FAIL: could not write %s\n", png.c_str());
    return ok;
  }
};

int main(int argc, char **argv) {
  Options options;
  if (!parse_options(argc, argv, options)) return 1;
  if (options.reversed) {
    std::fprintf(stderr, "FAIL: --reversed: Irrlicht 1.8 has no reversed-Z depth setup\n");
    return 1;
  }

  SIrrlichtCreationParameters params;
  params.DriverType = video::EDT_OPENGL;
  params.WindowSize = core::dimension2du(kWidth, kHeight);
  params.Bits = 32;
  params.ZBufferBits = kDepthBits;
  params.Stencilbuffer = false;
  params.AntiAlias = 0;
  params.Vsync = false;
  params.LoggingLevel = ELL_WARNING;
  params.Doublebuffer = false; // createScreenShot reads GL_FRONT, which Mesa under Xvfb leaves
                               // black after a swap: draw straight into it
  IrrlichtDevice *device = createDeviceEx(params);
  if (!device) {
    std::fprintf(stderr, "FAIL: Irrlicht could not open a %dx%d OpenGL window\n", kWidth, kHeight);
    return 1;
  }
  scene::ISceneManager *smgr = device->getSceneManager();

  GLint depth_bits = 0, subpixel_bits = 0;
  glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
  glGetIntegerv(GL_SUBPIXEL_BITS, &subpixel_bits);
  std::printf("Irrlicht %s on %s; depth bits %d, subpixel bits %d\n", device->getVersion(),
              (const char *)glGetString(GL_RENDERER), depth_bits, subpixel_bits);
  if (options.subpixel_bits != kAskGL) subpixel_bits = options.subpixel_bits;
  if (!known_depth_bits(depth_bits)) {
    device->drop();
    return 1;
  }

  const video::SColor blue(255, 0, 0, 255);
  scene::IMeshSceneNode *ground = add_rectangle(smgr, kGround, 0.0, blue);
  scene::IMeshSceneNode *tiles = add_rectangle(smgr, kGround, kViews[1].ground_tile, blue);
  scene::IMeshSceneNode *occluder = add_rectangle(smgr, kOccluder, 0.0, video::SColor(255, 255, 255, 0));
  scene::SMeshBuffer decal;
  fill(decal, kDecal, 0.0, video::SColor(255, 255, 0, 0));

  scene::ICameraSceneNode *camera = smgr->addCameraSceneNode();
  camera->setFOV((f32)(kFovyDegrees * M_PI / 180.0));
  camera->setAspectRatio((f32)kWidth / kHeight);
  camera->setNearValue((f32)kNear);
  camera->setFarValue((f32)kFar);
  const core::matrix4 projection = camera->getProjectionMatrix();
  core::matrix4 zshift_projection, over_projection;

  Frame frame = {device, camera, &decal, &projection, false};
  Engine engine;
  engine.depth_test = "GL_LEQUAL"; // SMaterial::ZBuffer's default, ECFN_LESSEQUAL
  const View *current = &kViews[0];
  engine.show_base = [&](bool on) {
    ground->setVisible(on && current->ground_tile == 0.0);
    tiles->setVisible(on && current->ground_tile != 0.0);
    occluder->setVisible(on);
  };
  engine.show_decal = [&](bool on) { frame.decal_shown = on; };
  engine.decal_projection = [&](Method m) {
    frame.decal_projection = m == kNoOffset ? &projection : m == kZshift ? &zshift_projection : &over_projection;
  };
  engine.shoot = [&](Picture &out, const std::string &png) { return frame.shoot(out, png); };

  int failed = 0;
  for (const View &view : kViews) {
    current = &view;
    Axes a = axes(view);
    camera->setPosition(core::vector3df((f32)view.eye[0], (f32)view.eye[1], (f32)-view.eye[2]));
    camera->setTarget(core::vector3df((f32)view.target[0], (f32)view.target[1], (f32)-view.target[2]));
    camera->setUpVector(core::vector3df((f32)a.up[0], (f32)a.up[1], (f32)-a.up[2]));
    camera->updateAbsolutePosition();
    smgr->drawAll(); // the camera computes its view matrix as it draws
    engine.name = "Irrlicht D" + std::to_string(depth_bits) + " " + view.name;
    std::printf("%s: ", engine.name.c_str());

    // What the engine knows about its decal, from the camera's view matrix (left-handed: +z ahead).
    double view_matrix[16];
    for (int i = 0; i < 16; i++) view_matrix[i] = camera->getViewMatrix()[i];
    float decal_corners[4][3];
    corners(kDecal, -1.0, decal_corners);
    DecalExtent ext = decal_extent(view_matrix, decal_corners, 1.0);
    ZshiftDecal decal_info =
        describe_decal(unorm_format(depth_bits), subpixel_bits, ext, ground_reach(view_matrix, -1.0, view));
    if (!zshift_decal_projection(*camera, decal_info, zshift_projection)) {
      device->drop();
      return 1;
    }
    const float *m = projection.pointer(), *z = zshift_projection.pointer();
    print_changed(m, z);
    engine.bleed_gap = bleed_gap(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, decal_info);
    engine.occluder_gap = occluder_gap(view);
    float over[16];
    if (!control_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, engine.occluder_gap, ext, over)) {
      device->drop();
      return 1;
    }
    over_projection.setM(over);
    failed |= compare(engine, options.out_dir,
                      "irrlicht_d" + std::to_string(depth_bits) + "_" + view.name + "_");
  }
  device->drop();
  return failed;
}
