// An OpenSceneGraph 3.6 program drawing a decal with zshift's projection.
//
// The ground and the occluder are drawn with the camera's own projection; the decal subgraph
// sits under an osg::Projection node whose matrix is zshift's decal matrix, built from the
// camera's projection. For each view of the scene (README, "Inside real engines") the program
// renders with no offset and with zshift's matrix into a framebuffer object with the depth
// format asked for, reads every frame back through the camera-attached osg::Image, saves the
// pictures and exits nonzero unless the decal z-fights without an offset and loses no pixel
// (and bleeds through no occluder beyond zshift's bleed gap) with zshift's.
//
// Usage: decal_osg [--depth 16|24|32 | --reversed] [--subpixel-bits B] [OUTPUT_DIR]   (OSG opens
// an X11 window: run it under xvfb-run). --reversed draws with reversed Z, as modern engines do:
// glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) (osg::ClipControl), an infinite far plane,
// GL_GREATER, depth cleared to 0, a 32-bit float depth buffer.
#include <osg/ClipControl>
#include <osg/Depth>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/GL>
#include <osg/Projection>
#include <osgDB/WriteFile>
#include <osgViewer/Viewer>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "zshift.h"

#include "../common/decal_scene.h"
#include "osg_frame.h"

using namespace decal_scene;

// [quickstart-engines-osg]
// zshift inside OpenSceneGraph: the decal subgraph's projection, from the camera's own (the one
// the ground is drawn with, for the depth convention `clip`): one element changes (10, or 14
// under reversed Z), by just enough to beat the rasterizer's rounding for `decal`. Put the
// decal under osg::Projection(decal_projection), drawn after the surface it lies on.
static bool zshift_decal_projection(const osg::Matrixd &camera_projection, ZshiftClip clip,
                                    const ZshiftDecal &decal, osg::Matrixd &decal_projection) {
  float m[16], out[16]; // column-major: osg::Matrix's memory order too
  for (int i = 0; i < 16; i++) m[i] = (float)camera_projection.ptr()[i]; // what GL gets
  if (zshift_decal_matrix(m, clip, &decal, out) != ZSHIFT_OK) {
    std::cerr << "zshift_decal_matrix: " << zshift_last_error() << "\n";
    return false;
  }
  decal_projection.set(out);
  return true;
}
// [/quickstart-engines-osg]

static osg::Geode *rectangle(const Rect &r, double tile, const osg::Vec4 &color) {
  std::vector<float> xyz = triangles(r, tile, 1.0);
  osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
  for (size_t i = 0; i < xyz.size(); i += 3) v->push_back(osg::Vec3(xyz[i], xyz[i + 1], xyz[i + 2]));
  osg::ref_ptr<osg::Vec4Array> colors = new osg::Vec4Array;
  colors->push_back(color);
  osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
  g->setVertexArray(v.get());
  g->setColorArray(colors.get(), osg::Array::BIND_OVERALL);
  g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, (GLsizei)v->size()));
  g->setCullingActive(false);
  g->setUseDisplayList(false); // draw callbacks then run at draw time, inside the FBO
  osg::Geode *geode = new osg::Geode;
  geode->addDrawable(g.get());
  return geode;
}

int main(int argc, char **argv) {
  Options options;
  if (!parse_options(argc, argv, options)) return 1;
  const bool reversed = options.reversed;
  const int depth_bits = reversed ? 32 : options.depth_bits;
  const ZshiftClip clip = reversed ? ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE : ZSHIFT_CLIP_NEG_ONE_TO_ONE;
  const ZshiftFormat format = reversed ? ZSHIFT_FORMAT_FLOAT32 : unorm_format(depth_bits);
  const std::string buffer = reversed ? "D32F reversed" : "D" + std::to_string(depth_bits);

  osg::ref_ptr<osg::GraphicsContext> gc = open_window();
  if (!gc.valid()) return 1;
  osgViewer::Viewer viewer;
  osg::Camera *camera = window_camera(viewer, gc.get());
  const double aspect = (double)kWidth / kHeight;
  if (reversed) {
    // [quickstart-engines-osg-reversed]
    // Reversed Z with the far plane at infinity: NDC depth n/d on a [0, 1] clip range, 1 at the
    // near plane, 0 far away; nearer is greater; cleared to 0. The decal's matrix then comes from
    // zshift_decal_projection(projection, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, decal, ...) with
    // decal.format = ZSHIFT_FORMAT_FLOAT32 (GL_DEPTH_COMPONENT32F).
    double y = 1.0 / std::tan(kFovyDegrees * M_PI / 360.0);
    camera->setProjectionMatrix(osg::Matrixd(y / aspect, 0, 0, 0, 0, y, 0, 0, 0, 0, 0, -1, 0, 0, kNear, 0));
    camera->setClearDepth(0.0);
    osg::StateSet *state = camera->getOrCreateStateSet();
    state->setAttributeAndModes(new osg::ClipControl(osg::ClipControl::LOWER_LEFT, osg::ClipControl::ZERO_TO_ONE));
    state->setAttributeAndModes(new osg::Depth(osg::Depth::GREATER));
    // [/quickstart-engines-osg-reversed]
  } else {
    camera->setProjectionMatrixAsPerspective(kFovyDegrees, aspect, kNear, kFar);
  }
  // [quickstart-engines-osg-near-far]
  // By default OSG refits near and far to the scene's bounds every frame, so the projection it
  // draws with is not the one set here; the decal's is derived from it, so keep it fixed.
  camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
  // [/quickstart-engines-osg-near-far]
  camera->setCullingMode(camera->getCullingMode() & ~osg::CullSettings::SMALL_FEATURE_CULLING);
  const GLenum depth_format = reversed           ? GL_DEPTH_COMPONENT32F
                              : depth_bits == 16 ? GL_DEPTH_COMPONENT16
                              : depth_bits == 24 ? GL_DEPTH_COMPONENT24
                                                 : GL_DEPTH_COMPONENT32;
  osg::ref_ptr<osg::Image> image = render_to_image(camera, depth_format);

  osg::ref_ptr<osg::Group> root = new osg::Group;
  root->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
  osg::ref_ptr<osg::Geode> ground = rectangle(kGround, 0.0, osg::Vec4(0, 0, 1, 1));
  osg::ref_ptr<osg::Geode> tiles = rectangle(kGround, kViews[1].ground_tile, osg::Vec4(0, 0, 1, 1));
  osg::ref_ptr<osg::Geode> occluder = rectangle(kOccluder, 0.0, osg::Vec4(1, 1, 0, 1));
  osg::ref_ptr<osg::Geode> decal = rectangle(kDecal, 0.0, osg::Vec4(1, 0, 0, 1));
  root->addChild(ground.get());
  root->addChild(tiles.get());
  root->addChild(occluder.get());
  // [quickstart-engines-osg-graph]
  // The decal's subgraph under its own projection, drawn after the ground (render bin 1 follows
  // the default bin 0); decal_node->setMatrix(zshift's matrix) once the context is up.
  osg::ref_ptr<osg::Projection> decal_node = new osg::Projection;
  decal_node->addChild(decal.get());
  decal_node->getOrCreateStateSet()->setRenderBinDetails(1, "RenderBin");
  root->addChild(decal_node.get());
  // [/quickstart-engines-osg-graph]
  viewer.setSceneData(root.get());
  viewer.realize();
  if (!viewer.isRealized()) {
    std::cerr << "FAIL: the OpenSceneGraph viewer could not be realized\n";
    return 1;
  }

  // One frame, then ask GL what the framebuffer object really has.
  osg::ref_ptr<DepthBits> probe = new DepthBits;
  osg::Drawable *ground_drawable = ground->getDrawable(0);
  ground_drawable->setDrawCallback(probe.get());
  Picture first;
  if (!shoot(viewer, *image, first, "")) return 1;
  ground_drawable->setDrawCallback(nullptr);
  std::printf("OpenSceneGraph %s on %s; framebuffer object depth bits %d, subpixel bits %d\n",
              osgGetVersion(), probe->renderer.c_str(), probe->bits, probe->subpixel_bits);
  if (probe->bits != depth_bits) { // GL_DEPTH_COMPONENT32F has 32 too
    std::fprintf(stderr, "FAIL: the framebuffer object has %d depth bits, not %d\n", probe->bits,
                 depth_bits);
    return 1;
  }
  int subpixel_bits = options.subpixel_bits == kAskGL ? probe->subpixel_bits : options.subpixel_bits;

  const osg::Matrixd projection = camera->getProjectionMatrix();
  osg::Matrixd zshift_projection, over_projection;
  Engine engine;
  engine.depth_test = reversed ? "GL_GREATER" : "GL_LESS";
  engine.ties_test = reversed ? "GL_GEQUAL" : "GL_LEQUAL";
  const View *current = &kViews[0];
  engine.show_base = [&](bool on) {
    ground->setNodeMask(on && current->ground_tile == 0.0 ? ~0u : 0u);
    tiles->setNodeMask(on && current->ground_tile != 0.0 ? ~0u : 0u);
    occluder->setNodeMask(on ? ~0u : 0u);
  };
  engine.show_decal = [&](bool on) { decal_node->setNodeMask(on ? ~0u : 0u); };
  engine.decal_projection = [&](Method m) {
    decal_node->setMatrix(m == kNoOffset ? projection : m == kZshift ? zshift_projection : over_projection);
  };
  engine.decal_ties = [&](bool on) {
    osg::Depth::Function ties = reversed ? osg::Depth::GEQUAL : osg::Depth::LEQUAL;
    if (on) decal_node->getOrCreateStateSet()->setAttributeAndModes(new osg::Depth(ties));
    else decal_node->getOrCreateStateSet()->removeAttribute(osg::StateAttribute::DEPTH);
  };
  engine.shoot = [&](Picture &out, const std::string &png) { return shoot(viewer, *image, out, png); };

  int failed = 0;
  for (const View &view : kViews) {
    current = &view;
    Axes a = axes(view);
    camera->setViewMatrixAsLookAt(osg::Vec3d(view.eye[0], view.eye[1], view.eye[2]),
                                  osg::Vec3d(view.target[0], view.target[1], view.target[2]),
                                  osg::Vec3d(a.up[0], a.up[1], a.up[2]));
    engine.name = "OSG " + buffer + " " + view.name;
    std::printf("%s: ", engine.name.c_str());
    // What the engine knows about its decal, from the camera's view matrix.
    float decal_corners[4][3];
    corners(kDecal, 1.0, decal_corners);
    DecalExtent ext = decal_extent(camera->getViewMatrix().ptr(), decal_corners, -1.0);
    ZshiftDecal decal =
        describe_decal(format, subpixel_bits, ext, ground_reach(camera->getViewMatrix().ptr(), 1.0, view));
    if (!zshift_decal_projection(projection, clip, decal, zshift_projection)) return 1;
    float m[16], z[16], over[16];
    for (int i = 0; i < 16; i++) {
      m[i] = (float)projection.ptr()[i];
      z[i] = (float)zshift_projection.ptr()[i];
    }
    print_changed(m, z);
    engine.bleed_gap = bleed_gap(m, clip, decal);
    engine.occluder_gap = occluder_gap(view);
    if (!control_matrix(m, clip, engine.occluder_gap, ext, over)) return 1;
    over_projection.set(over);
    std::string tag = buffer + "_" + view.name + "_";
    std::replace(tag.begin(), tag.end(), ' ', '_');
    failed |= compare(engine, options.out_dir, "osg_" + tag);
  }
  return failed;
}
