// An OpenSceneGraph 3.6 program drawing a mesh's edges over its shaded faces with zshift's values.
//
// A UV sphere (24 x 12, every triangle edge drawn) as OSG users draw wireframe on shaded: the faces
// as an osg::Geometry of GL_TRIANGLES, the edges as an osg::Geometry of 1-pixel GL_LINES drawn after
// them (render bin 1) under GL_LEQUAL and an osg::Projection node. Four ways:
//   none       no offset;
//   (1,1)      the common practice (osgFX::Scribe, three.js): osg::PolygonOffset(1, 1) on the faces;
//   zshift (a) osg::PolygonOffset(factor, units) on the faces from zshift_edge_offset(...,
//              ZSHIFT_EDGES_POLYGON_OFFSET, ...);
//   zshift (b) the edges' osg::Projection set to the matrix of zshift_edge_offset(...,
//              ZSHIFT_EDGES_MATRIX, ...), faces unoffset;
// and a control: the edges pulled forward by the sphere's radius, which must show hidden edges.
//
// The reference is built by construction, in f64: the sphere is convex and closed, so an edge
// whose two triangles both face the camera is visible, one whose two triangles both face away is
// hidden, and the rest are the silhouette (not counted). Three ID renders (each class alone, depth
// test off, the edge's index in the colour) say which edge covers which pixel; an f64 z-buffer of
// the triangles' exact planes says which triangle is in front at each pixel centre. A visible-edge
// pixel counts where the triangle in front is one of the edge's two, no vertex lies within 2
// pixels and that triangle's window-depth gradient is within zshift's face_gradient (faces steeper
// than the limit are not promised); it is *lost* unless the scene shows an edge there. A hidden-edge
// pixel counts where no visible or silhouette edge covers it, no vertex lies within 2 pixels and the
// front triangle is within the gradient limit; its separation is the least eye depth by which the
// edge (anywhere on it within 1.5 pixels of the pixel centre, where a line fragment takes its
// depth) lies behind the front triangle's plane at the pixel centre. It is *shown* when the scene
// shows the hidden edges' colour there; *shown beyond the gap* when, besides, its separation is at
// least zshift's hidden_gap.
//
// Exits nonzero unless, in every scene: no offset loses visible-edge pixels; zshift (a) and (b)
// lose none and show no hidden-edge pixel beyond their gap; and the control shows hidden pixels
// beyond the gap (so the check can fail).
//
// Usage: edges_osg [--depth 16|24|32] [--subpixel-bits B] [OUTPUT_DIR]   (under xvfb-run; the
// pictures go to OUTPUT_DIR; EDGES_OSG_VERBOSE=1 prints each lost pixel)
#include <osg/Depth>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/GL>
#include <osg/PolygonOffset>
#include <osg/Projection>
#include <osgDB/WriteFile>
#include <osgViewer/Viewer>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "zshift.h"

#include "../common/decal_scene.h"
#include "osg_frame.h"

using decal_scene::kFovyDegrees;
using decal_scene::kHeight;
using decal_scene::kWidth;
using decal_scene::Picture;

// The sphere: centre on the line of sight at eye depth `distance`, `radius`, camera at the origin
// looking down -z (the view matrix is the identity: eye space is world space), planes near/far.
struct Scene {
  const char *name;
  double distance, radius, near, far;
};
const Scene kScenes[] = {
    {"near f/n 1e3", 2.5, 0.75, 0.1, 100.0},
    {"middle f/n 1e4", 100.0, 30.0, 0.1, 1000.0},
    {"far f/n 1e4", 800.0, 150.0, 0.1, 1000.0},
};
const int kSegments = 24, kRings = 12;
const double kFaceAngle = 70.0 * M_PI / 180.0; // the steepest face whose edges must be kept

struct Mesh {
  std::vector<std::array<double, 3>> v; // eye space, the f32 values GL gets
  std::vector<std::array<int, 3>> tri;  // counter-clockwise seen from outside
  std::vector<std::array<int, 2>> edge;
  std::vector<std::array<int, 2>> edge_tris;
};

static Mesh sphere(const Scene &s) {
  Mesh m;
  const double tilt_x = 35.0 * M_PI / 180.0, tilt_y = 20.0 * M_PI / 180.0;
  auto place = [&](double x, double y, double z) {
    double y1 = std::cos(tilt_x) * y - std::sin(tilt_x) * z, z1 = std::sin(tilt_x) * y + std::cos(tilt_x) * z;
    double x2 = std::cos(tilt_y) * x + std::sin(tilt_y) * z1, z2 = -std::sin(tilt_y) * x + std::cos(tilt_y) * z1;
    m.v.push_back({(double)(float)(s.radius * x2), (double)(float)(s.radius * y1),
                   (double)(float)(s.radius * z2 - s.distance)});
  };
  place(0, 1, 0);
  for (int r = 1; r < kRings; r++) {
    double th = M_PI * r / kRings;
    for (int k = 0; k < kSegments; k++) {
      double ph = 2 * M_PI * k / kSegments;
      place(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
    }
  }
  place(0, -1, 0);
  const int south = (int)m.v.size() - 1;
  auto at = [&](int r, int k) { return 1 + (r - 1) * kSegments + (k % kSegments); };
  for (int k = 0; k < kSegments; k++) {
    m.tri.push_back({0, at(1, k), at(1, k + 1)});
    for (int r = 1; r + 1 < kRings; r++) {
      m.tri.push_back({at(r, k), at(r + 1, k), at(r + 1, k + 1)});
      m.tri.push_back({at(r, k), at(r + 1, k + 1), at(r, k + 1)});
    }
    m.tri.push_back({at(kRings - 1, k), south, at(kRings - 1, k + 1)});
  }
  std::map<std::pair<int, int>, int> index;
  for (int t = 0; t < (int)m.tri.size(); t++) {
    for (int i = 0; i < 3; i++) {
      int a = m.tri[t][i], b = m.tri[t][(i + 1) % 3];
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = index.find(key);
      if (it == index.end()) {
        index[key] = (int)m.edge.size();
        m.edge.push_back({a, b});
        m.edge_tris.push_back({t, -1});
      } else {
        m.edge_tris[it->second][1] = t;
      }
    }
  }
  return m;
}

static std::array<double, 3> sub(const std::array<double, 3> &a, const std::array<double, 3> &b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
static std::array<double, 3> cross3(const std::array<double, 3> &a, const std::array<double, 3> &b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
static double dot3(const std::array<double, 3> &a, const std::array<double, 3> &b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The f64 reference: each vertex in window coordinates (x, y in pixels, z window depth under
// [-1, 1] with glDepthRange(0, 1)), each triangle's plane, facing and window-depth gradient, and
// the triangle in front at each pixel centre with its eye depth.
enum EdgeClass { kVisible, kHidden, kSilhouette };
struct Reference {
  std::vector<std::array<double, 3>> win;
  std::vector<bool> front;
  std::vector<double> gradient;           // max(|dz/dx|, |dz/dy|) of window depth per pixel
  std::vector<EdgeClass> cls;
  std::vector<int> front_tri;             // per pixel, -1 for none
  std::vector<double> front_depth;        // eye depth (-z) of front_tri's plane at the centre
  std::vector<bool> near_vertex;          // a projected vertex within 2 pixels
};

static Reference reference(const Mesh &m, const float p[16]) {
  Reference r;
  for (const auto &v : m.v) {
    double cx = p[0] * v[0] + p[8] * v[2], cy = p[5] * v[1] + p[9] * v[2];
    double cz = p[10] * v[2] + p[14], w = -v[2];
    r.win.push_back({(cx / w + 1) / 2 * kWidth, (cy / w + 1) / 2 * kHeight, (cz / w + 1) / 2});
  }
  const int n = kWidth * kHeight;
  r.front_tri.assign(n, -1);
  r.front_depth.assign(n, INFINITY);
  r.near_vertex.assign(n, false);
  for (const auto &t : m.tri) {
    auto nrm = cross3(sub(m.v[t[1]], m.v[t[0]]), sub(m.v[t[2]], m.v[t[0]]));
    r.front.push_back(dot3(nrm, m.v[t[0]]) < 0); // the eye is at the origin
    const auto &a = r.win[t[0]], &b = r.win[t[1]], &c = r.win[t[2]];
    double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    double gx = ((b[2] - a[2]) * (c[1] - a[1]) - (c[2] - a[2]) * (b[1] - a[1])) / det;
    double gy = ((c[2] - a[2]) * (b[0] - a[0]) - (b[2] - a[2]) * (c[0] - a[0])) / det;
    r.gradient.push_back(std::max(std::fabs(gx), std::fabs(gy)));
  }
  for (int t = 0; t < (int)m.tri.size(); t++) {
    const auto &a = r.win[m.tri[t][0]], &b = r.win[m.tri[t][1]], &c = r.win[m.tri[t][2]];
    auto nrm = cross3(sub(m.v[m.tri[t][1]], m.v[m.tri[t][0]]), sub(m.v[m.tri[t][2]], m.v[m.tri[t][0]]));
    double x0 = std::max(0.0, std::floor(std::min({a[0], b[0], c[0]})));
    double x1 = std::min(kWidth - 1.0, std::ceil(std::max({a[0], b[0], c[0]})));
    double y0 = std::max(0.0, std::floor(std::min({a[1], b[1], c[1]})));
    double y1 = std::min(kHeight - 1.0, std::ceil(std::max({a[1], b[1], c[1]})));
    auto side = [](const std::array<double, 3> &u, const std::array<double, 3> &w, double x, double y) {
      return (w[0] - u[0]) * (y - u[1]) - (w[1] - u[1]) * (x - u[0]);
    };
    for (int y = (int)y0; y <= (int)y1; y++) {
      for (int x = (int)x0; x <= (int)x1; x++) {
        double px = x + 0.5, py = y + 0.5;
        double e0 = side(a, b, px, py), e1 = side(b, c, px, py), e2 = side(c, a, px, py);
        if (!((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0))) continue;
        // The ray through the pixel centre, at eye depth d: (xn d / p0, yn d / p5, -d).
        double xn = px / kWidth * 2 - 1, yn = py / kHeight * 2 - 1;
        std::array<double, 3> dir = {xn / p[0], yn / p[5], -1.0};
        double d = dot3(nrm, m.v[m.tri[t][0]]) / dot3(nrm, dir);
        int i = y * kWidth + x;
        if (d < r.front_depth[i]) {
          r.front_depth[i] = d;
          r.front_tri[i] = t;
        }
      }
    }
  }
  for (const auto &w : r.win) {
    for (int y = (int)std::floor(w[1] - 2); y <= (int)std::ceil(w[1] + 2); y++)
      for (int x = (int)std::floor(w[0] - 2); x <= (int)std::ceil(w[0] + 2); x++)
        if (x >= 0 && y >= 0 && x < kWidth && y < kHeight &&
            std::hypot(x + 0.5 - w[0], y + 0.5 - w[1]) <= 2.0)
          r.near_vertex[y * kWidth + x] = true;
  }
  for (const auto &et : m.edge_tris) {
    bool f0 = r.front[et[0]], f1 = r.front[et[1]];
    r.cls.push_back(f0 && f1 ? kVisible : !f0 && !f1 ? kHidden : kSilhouette);
  }
  return r;
}

// The least eye depth of edge `e` within 1.5 pixels of the centre of pixel (x, y): 1/depth is
// linear along the projected segment.
static double edge_depth_near(const Mesh &m, const Reference &r, int e, int x, int y) {
  const auto &a = r.win[m.edge[e][0]], &b = r.win[m.edge[e][1]];
  double da = -m.v[m.edge[e][0]][2], db = -m.v[m.edge[e][1]][2];
  double len = std::hypot(b[0] - a[0], b[1] - a[1]);
  int steps = std::max(2, (int)std::ceil(len * 20));
  double best = INFINITY;
  for (int i = 0; i <= steps; i++) {
    double t = (double)i / steps;
    double sx = a[0] + t * (b[0] - a[0]), sy = a[1] + t * (b[1] - a[1]);
    if (std::hypot(sx - (x + 0.5), sy - (y + 0.5)) > 1.5) continue;
    best = std::min(best, 1.0 / ((1 - t) / da + t / db));
  }
  return best;
}

// osg::Geometry helpers. IDs: edge index + 1 in red (low byte) and green (high byte).
static osg::Geometry *geometry(const Mesh &m, GLenum mode, const std::vector<int> &items,
                               const std::function<osg::Vec4(int)> &color) {
  osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
  osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
  for (int it : items) {
    int k = mode == GL_TRIANGLES ? 3 : 2;
    for (int i = 0; i < k; i++) {
      int vi = mode == GL_TRIANGLES ? m.tri[it][i] : m.edge[it][i];
      v->push_back(osg::Vec3((float)m.v[vi][0], (float)m.v[vi][1], (float)m.v[vi][2]));
      c->push_back(color(it));
    }
  }
  osg::Geometry *g = new osg::Geometry;
  g->setVertexArray(v.get());
  g->setColorArray(c.get(), osg::Array::BIND_PER_VERTEX);
  g->addPrimitiveSet(new osg::DrawArrays(mode, 0, (GLsizei)v->size()));
  g->setCullingActive(false);
  return g;
}

// [quickstart-engines-osg-edges]
// zshift inside OpenSceneGraph for edges over their own faces: what the engine knows about its
// mesh (viewport, depth format, its eye-depth range, 1-pixel GL_LINES under GL_LEQUAL, the
// steepest face whose edges must be kept), and the offset by `method`:
// ZSHIFT_EDGES_POLYGON_OFFSET: faces->getOrCreateStateSet()->setAttributeAndModes(
//     new osg::PolygonOffset(out.polygon_offset[0], out.polygon_offset[1]));
// ZSHIFT_EDGES_MATRIX: the edges under osg::Projection(osg::Matrixd(out.matrix)).
static bool zshift_edges(const osg::Matrixd &camera_projection, ZshiftFormat format, int subpixel_bits,
                         double depth_near, double depth_far, uint32_t method, ZshiftEdgeOffset &out) {
  float m[16]; // column-major: osg::Matrix's memory order too
  for (int i = 0; i < 16; i++) m[i] = (float)camera_projection.ptr()[i];
  ZshiftEdges edges = {};
  edges.viewport_width = kWidth;
  edges.viewport_height = kHeight;
  edges.format = format;
  edges.subpixel_bits = subpixel_bits;
  edges.depth_near = depth_near;
  edges.depth_far = depth_far;
  edges.line_width = 1.0;   // glLineWidth
  edges.polygon_mode = 0;   // GL_LINES
  edges.samples = 1;        // no MSAA
  edges.face_angle = kFaceAngle;
  edges.depth_func = ZSHIFT_DEPTH_TEST_LEQUAL;
  edges.profile = nullptr;  // the worst case with subpixel_bits
  if (zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &edges, method, &out) != ZSHIFT_OK) {
    std::cerr << "zshift_edge_offset: " << zshift_last_error() << "\n";
    return false;
  }
  return true;
}
// [/quickstart-engines-osg-edges]

struct Count {
  int visible = 0, lost = 0;             // visible-edge pixels counted, and lost
  int hidden = 0, shown = 0;             // hidden-edge pixels counted, and shown
  int checkable = 0, shown_beyond = 0;   // ... behind the front face by at least the gap
  int steep = 0;                         // edge pixels over faces steeper than the limit, not counted
};

static bool is_red(const unsigned char *p) { return p[0] == 255 && p[1] == 0 && p[2] == 0; }
static bool is_green(const unsigned char *p) { return p[0] == 0 && p[1] == 255 && p[2] == 0; }
static int id_at(const Picture &pic, int x, int y) {
  const unsigned char *p = pic.at(x, y);
  return p[0] + 256 * p[1] - 1;
}

int main(int argc, char **argv) {
  decal_scene::Options options;
  if (!decal_scene::parse_options(argc, argv, options)) return 1;
  if (options.reversed) {
    std::fprintf(stderr, "FAIL: edges_osg draws under [-1, 1] only\n");
    return 1;
  }
  const int depth_bits = options.depth_bits;
  const ZshiftFormat format = decal_scene::unorm_format(depth_bits);
  const std::string buffer = "D" + std::to_string(depth_bits);

  osg::ref_ptr<osg::GraphicsContext> gc = open_window();
  if (!gc.valid()) return 1;
  osgViewer::Viewer viewer;
  osg::Camera *camera = window_camera(viewer, gc.get());
  camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
  camera->setCullingMode(camera->getCullingMode() & ~osg::CullSettings::SMALL_FEATURE_CULLING);
  camera->setViewMatrix(osg::Matrixd::identity());
  const GLenum depth_format = depth_bits == 16 ? GL_DEPTH_COMPONENT16
                              : depth_bits == 24 ? GL_DEPTH_COMPONENT24
                                                 : GL_DEPTH_COMPONENT32;
  osg::ref_ptr<osg::Image> image = render_to_image(camera, depth_format);
  const double aspect = (double)kWidth / kHeight;
  camera->setProjectionMatrixAsPerspective(kFovyDegrees, aspect, kScenes[0].near, kScenes[0].far);
  // Something to draw for the first frame, which also asks GL what the FBO has.
  osg::ref_ptr<osg::Geode> first_geode = new osg::Geode;
  {
    Mesh m0 = sphere(kScenes[0]);
    std::vector<int> all(m0.tri.size());
    for (size_t i = 0; i < all.size(); i++) all[i] = (int)i;
    first_geode->addDrawable(geometry(m0, GL_TRIANGLES, all, [](int) { return osg::Vec4(1, 1, 1, 1); }));
  }
  osg::ref_ptr<DepthBits> probe = new DepthBits;
  first_geode->getDrawable(0)->asGeometry()->setUseDisplayList(false);
  first_geode->getDrawable(0)->setDrawCallback(probe.get());
  viewer.setSceneData(first_geode.get());
  viewer.realize();
  if (!viewer.isRealized()) {
    std::cerr << "FAIL: the OpenSceneGraph viewer could not be realized\n";
    return 1;
  }
  Picture pic;
  if (!shoot(viewer, *image, pic, "")) return 1;
  std::printf("OpenSceneGraph %s on %s; framebuffer object depth bits %d, subpixel bits %d\n", osgGetVersion(),
              probe->renderer.c_str(), probe->bits, probe->subpixel_bits);
  if (probe->bits != depth_bits) {
    std::fprintf(stderr, "FAIL: the framebuffer object has %d depth bits, not %d\n", probe->bits, depth_bits);
    return 1;
  }
  const int subpixel_bits =
      options.subpixel_bits == decal_scene::kAskGL ? probe->subpixel_bits : options.subpixel_bits;

  int failed = 0;
  for (const Scene &s : kScenes) {
    camera->setProjectionMatrixAsPerspective(kFovyDegrees, aspect, s.near, s.far);
    const osg::Matrixd projection = camera->getProjectionMatrix();
    float pf[16];
    for (int i = 0; i < 16; i++) pf[i] = (float)projection.ptr()[i];
    Mesh mesh = sphere(s);
    Reference ref = reference(mesh, pf);
    double depth_near = INFINITY, depth_far = 0;
    for (const auto &v : mesh.v) {
      depth_near = std::min(depth_near, -v[2]);
      depth_far = std::max(depth_far, -v[2]);
    }
    ZshiftEdgeOffset za, zb;
    if (!zshift_edges(projection, format, subpixel_bits, depth_near, depth_far, ZSHIFT_EDGES_POLYGON_OFFSET, za) ||
        !zshift_edges(projection, format, subpixel_bits, depth_near, depth_far, ZSHIFT_EDGES_MATRIX, zb))
      return 1;
    const double g = za.face_gradient; // the same limit for both methods

    // The control: element 10 moved the way zshift's moves it, by enough to pull the nearest
    // vertex forward by the radius (farther ones by more).
    osg::Matrixd control = projection;
    double ndc_pull = std::fabs(pf[14]) / (depth_near * depth_near) * s.radius;
    control.ptr()[10] = pf[10] + (zb.matrix[10] > pf[10] ? 1 : -1) * ndc_pull;

    // The scene graph: faces, then edges (visible and silhouette red, hidden green) under a
    // projection node in render bin 1, GL_LEQUAL; and each class again with its IDs for the
    // reference renders (depth test off).
    std::vector<int> tris(mesh.tri.size()), by_class[3];
    for (size_t i = 0; i < tris.size(); i++) tris[i] = (int)i;
    for (int e = 0; e < (int)mesh.edge.size(); e++) by_class[ref.cls[e]].push_back(e);
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    osg::ref_ptr<osg::Geode> faces = new osg::Geode;
    faces->addDrawable(geometry(mesh, GL_TRIANGLES, tris, [&](int t) {
      auto n = cross3(sub(mesh.v[mesh.tri[t][1]], mesh.v[mesh.tri[t][0]]),
                      sub(mesh.v[mesh.tri[t][2]], mesh.v[mesh.tri[t][0]]));
      double l = std::sqrt(dot3(n, n));
      float shade = (float)(0.25 + 0.6 * std::max(0.0, (0.3 * n[0] + 0.5 * n[1] + 0.81 * n[2]) / l));
      return osg::Vec4(shade, shade, shade, 1);
    }));
    root->addChild(faces.get());
    // [quickstart-engines-osg-edges-graph]
    // The edges (GL_LINES) after the faces (render bin 1), under GL_LEQUAL and their own
    // projection: the camera's, or zshift's matrix for ZSHIFT_EDGES_MATRIX.
    osg::ref_ptr<osg::Projection> edge_node = new osg::Projection;
    osg::ref_ptr<osg::Geode> edges = new osg::Geode;
    edges->addDrawable(geometry(mesh, GL_LINES, by_class[kVisible], [](int) { return osg::Vec4(1, 0, 0, 1); }));
    edges->addDrawable(geometry(mesh, GL_LINES, by_class[kSilhouette], [](int) { return osg::Vec4(1, 0, 0, 1); }));
    edges->addDrawable(geometry(mesh, GL_LINES, by_class[kHidden], [](int) { return osg::Vec4(0, 1, 0, 1); }));
    edges->getOrCreateStateSet()->setAttributeAndModes(new osg::Depth(osg::Depth::LEQUAL));
    edge_node->addChild(edges.get());
    edge_node->getOrCreateStateSet()->setRenderBinDetails(1, "RenderBin");
    root->addChild(edge_node.get());
    // [/quickstart-engines-osg-edges-graph]
    osg::ref_ptr<osg::Geode> ids[3];
    for (int k = 0; k < 3; k++) {
      ids[k] = new osg::Geode;
      ids[k]->addDrawable(geometry(mesh, GL_LINES, by_class[k], [](int e) {
        return osg::Vec4(((e + 1) & 255) / 255.0f, ((e + 1) >> 8) / 255.0f, 0, 1);
      }));
      ids[k]->getOrCreateStateSet()->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF);
      root->addChild(ids[k].get());
    }
    viewer.setSceneData(root.get());

    std::string tag = "edges_osg_" + buffer + "_" + s.name;
    std::replace(tag.begin(), tag.end(), ' ', '_');
    std::replace(tag.begin(), tag.end(), '/', '-');
    std::string dir = options.out_dir.empty() ? "" : options.out_dir + "/";

    // The ID renders.
    Picture id[3];
    faces->setNodeMask(0);
    edge_node->setNodeMask(0);
    for (int k = 0; k < 3; k++) {
      for (int j = 0; j < 3; j++) ids[j]->setNodeMask(j == k ? ~0u : 0u);
      if (!shoot(viewer, *image, id[k], "")) return 1;
    }
    for (int j = 0; j < 3; j++) ids[j]->setNodeMask(0);
    faces->setNodeMask(~0u);
    edge_node->setNodeMask(~0u);

    auto tally = [&](const Picture &scene, double gap) {
      Count c;
      for (int y = 0; y < kHeight; y++) {
        for (int x = 0; x < kWidth; x++) {
          int i = y * kWidth + x, front = ref.front_tri[i];
          if (ref.near_vertex[i] || front < 0 || !ref.front[front]) continue;
          int ev = id_at(id[kVisible], x, y), eh = id_at(id[kHidden], x, y), es = id_at(id[kSilhouette], x, y);
          if (ref.gradient[front] > g) {
            c.steep += (ev >= 0 || eh >= 0) && es < 0;
            continue;
          }
          const unsigned char *p = scene.at(x, y);
          if (ev >= 0 && es < 0) {
            if (mesh.edge_tris[ev][0] != front && mesh.edge_tris[ev][1] != front) continue;
            // A hidden edge across it, drawn after, may show there when it lies within the gap.
            if (eh >= 0 && edge_depth_near(mesh, ref, eh, x, y) - ref.front_depth[i] < gap) continue;
            c.visible++;
            if (!is_red(p)) {
              c.lost++;
              if (getenv("EDGES_OSG_VERBOSE"))
                std::printf("    lost (%d, %d): %d %d %d, edge %d, hidden %d\n", x, y, p[0], p[1], p[2], ev, eh);
            }
          } else if (ev < 0 && es < 0 && eh >= 0) {
            double sep = edge_depth_near(mesh, ref, eh, x, y) - ref.front_depth[i];
            c.hidden++;
            if (is_green(p)) c.shown++;
            if (sep >= gap) {
              c.checkable++;
              if (is_green(p)) c.shown_beyond++;
            }
          }
        }
      }
      return c;
    };

    struct Way {
      const char *name;
      double factor, units;
      const osg::Matrixd *edge_projection;
      double gap;
    };
    osg::Matrixd zshift_projection(zb.matrix);
    const Way ways[] = {{"none", 0, 0, &projection, 0},
                        {"(1,1)", 1, 1, &projection, 0},
                        {"zshift (a)", za.polygon_offset[0], za.polygon_offset[1], &projection, za.hidden_gap},
                        {"zshift (b)", 0, 0, &zshift_projection, zb.hidden_gap},
                        {"control", 0, 0, &control, za.hidden_gap}};
    std::printf("%s %s: sphere at %g (radius %g), %zu visible, %zu hidden, %zu silhouette edges; zshift (a) "
                "glPolygonOffset(%.4g, %.4g), gap %.4g; (b) element 10 %.9g -> %.9g, gap %.4g; face gradient "
                "limit %.3g\n",
                buffer.c_str(), s.name, s.distance, s.radius, by_class[kVisible].size(), by_class[kHidden].size(),
                by_class[kSilhouette].size(), za.polygon_offset[0], za.polygon_offset[1], za.hidden_gap, pf[10],
                zb.matrix[10], zb.hidden_gap, g);
    Count counts[5];
    for (int w = 0; w < 5; w++) {
      const Way &way = ways[w];
      // [quickstart-engines-osg-edges-apply]
      // (a): the faces pushed back by osg::PolygonOffset (GL_POLYGON_OFFSET_FILL on); (b): the
      // edges' projection node carries zshift's matrix.
      osg::StateSet *fs = faces->getOrCreateStateSet();
      if (way.factor != 0 || way.units != 0)
        fs->setAttributeAndModes(new osg::PolygonOffset((float)way.factor, (float)way.units));
      else
        fs->removeAttribute(osg::StateAttribute::POLYGONOFFSET);
      edge_node->setMatrix(*way.edge_projection);
      // [/quickstart-engines-osg-edges-apply]
      std::string name = way.name;
      name.erase(std::remove_if(name.begin(), name.end(), [](char ch) { return ch == '(' || ch == ')'; }),
                 name.end());
      std::replace(name.begin(), name.end(), ' ', '-');
      std::replace(name.begin(), name.end(), ',', '-');
      Picture scene;
      if (!shoot(viewer, *image, scene, dir.empty() ? "" : dir + tag + "_" + name + ".png")) return 1;
      // The peers' "shown" counts every hidden pixel; their gap column is zshift (a)'s.
      Count c = tally(scene, w < 2 ? za.hidden_gap : way.gap);
      counts[w] = c;
      std::printf("  %-10s lost %5d of %5d visible-edge px; shown %5d of %5d hidden-edge px, %5d of %5d beyond "
                  "the gap %.4g (%d px on steeper faces)\n",
                  way.name, c.lost, c.visible, c.shown, c.hidden, c.shown_beyond, c.checkable,
                  w < 2 ? za.hidden_gap : way.gap, c.steep);
    }
    const Count &none = counts[0], &a = counts[2], &b = counts[3], &ctl = counts[4];
    auto fail = [&](const char *why) {
      std::printf("FAIL: %s %s: %s\n", buffer.c_str(), s.name, why);
      failed = 1;
    };
    if (none.visible < 500) fail("fewer than 500 visible-edge pixels counted");
    if (none.lost == 0) fail("no offset lost no visible-edge pixel (the check could not fail)");
    if (a.lost || b.lost) fail("zshift lost visible-edge pixels");
    if (a.shown_beyond || b.shown_beyond) fail("zshift showed hidden-edge pixels beyond its gap");
    if (ctl.shown_beyond == 0)
      fail("the control (edges pulled forward by the radius) showed no hidden pixel beyond the gap");
  }
  return failed;
}
