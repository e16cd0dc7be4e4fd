// The decal scene every engine example draws, and the check of its pixels.
//
// A large ground plane (blue), a decal (red) lying on it, and a thin slab (yellow) floating a few
// centimetres above part of the decal, seen from the views in kViews. World space is y-up and
// right-handed (OpenGL's); an engine with a left-handed world (Irrlicht) mirrors z. The depth
// buffer is the one asked for where the program chooses it (OSG's framebuffer object: 24 or 16
// bits), else the window's; the depth test is the engine's default (GL_LESS or GL_LEQUAL).
//
// Each engine renders these frames per method (`compare` below) and reads each back with its
// own screenshot call:
//   scene     base, occluder, then the decal (the picture a user sees)
//   decal     the decal alone (where its pixels are: the reference footprint)
//   occluder  base and occluder without the decal, once (where the occluder covers)
// and, as a control, the scene with the decal lifted by twice the occluder's gap, which must bleed.
// A decal pixel is *lost* when it lies in the decal's footprint, outside the occluder, and the
// scene does not show it; it *bleeds* when the occluder covers it and the scene shows the decal.
#ifndef ZSHIFT_ENGINES_DECAL_SCENE_H
#define ZSHIFT_ENGINES_DECAL_SCENE_H

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "zshift.h"

namespace decal_scene {

const int kWidth = 640;
const int kHeight = 480;
const double kFovyDegrees = 45.0;
const double kNear = 0.1;
const double kFar = 1000.0;
const int kDepthBits = 24;

// Where the camera stands, what it looks at, how far it is rolled about its line of sight, and
// how the ground is drawn: one quad that crosses the near plane (ground_tile 0: the clipper
// makes its visible vertices), or square tiles of side ground_tile, as terrain is.
struct View {
  const char *name;
  double eye[3], target[3], roll_degrees, ground_tile;
};
const View kViews[] = {
    // eye height 3, looking at the ground 30 units ahead (5.7 degrees below horizontal)
    {"grazing", {0.0, 3.0, 0.0}, {0.0, 0.0, -30.0}, 0.0, 0.0},
    {"grazing-tiled", {0.0, 3.0, 0.0}, {0.0, 0.0, -30.0}, 0.0, 20.0},
    // from 25 units up, 40 degrees below horizontal: a gentler slope, a larger decal
    {"above-tiled", {0.0, 25.0, 0.0}, {0.0, 0.0, -30.0}, 0.0, 20.0},
    // off to the side, looking across the decal, banked 20 degrees: the plane tilts in x and y
    {"banked-tiled", {-6.0, 2.0, 0.0}, {2.0, 0.0, -30.0}, 20.0, 20.0},
};

// The camera's axes in world space: `forward` along the line of sight, `up` world up rolled by
// the view's roll, `right` = forward x up.
struct Axes {
  double forward[3], up[3], right[3];
};
inline void normalize(double v[3]) {
  double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; i++) v[i] /= l;
}
inline void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
inline Axes axes(const View &v) {
  Axes a;
  const double world_up[3] = {0.0, 1.0, 0.0};
  for (int i = 0; i < 3; i++) a.forward[i] = v.target[i] - v.eye[i];
  normalize(a.forward);
  double right0[3], up0[3];
  cross(a.forward, world_up, right0);
  normalize(right0);
  cross(right0, a.forward, up0);
  double r = v.roll_degrees * M_PI / 180.0;
  for (int i = 0; i < 3; i++) a.up[i] = std::cos(r) * up0[i] + std::sin(r) * right0[i];
  cross(a.forward, a.up, a.right);
  return a;
}

// Axis-aligned rectangles in a plane y = const: x0, x1, z0, z1, y.
struct Rect {
  double x0, x1, z0, z1, y;
};
const Rect kGround = {-500.0, 500.0, -500.0, 500.0, 0.0};
const Rect kDecal = {-3.0, 3.0, -40.0, -20.0, 0.0};
const Rect kOccluder = {0.0, 4.0, -34.0, -28.0, 0.05};

// The corners of a rectangle, counter-clockwise seen from above (z mirrored when z_sign < 0).
inline void corners(const Rect &r, double z_sign, float out[4][3]) {
  const double xz[4][2] = {{r.x0, r.z1}, {r.x1, r.z1}, {r.x1, r.z0}, {r.x0, r.z0}};
  for (int i = 0; i < 4; i++) {
    out[i][0] = (float)xz[i][0];
    out[i][1] = (float)r.y;
    out[i][2] = (float)(z_sign * xz[i][1]);
  }
}

// A triangle list (x y z per vertex, three vertices per triangle) covering a rectangle: two
// triangles (corners 0 1 2, 0 2 3), or two per square tile of side `tile` when tile > 0.
inline std::vector<float> triangles(const Rect &r, double tile, double z_sign) {
  std::vector<float> out;
  int nx = tile > 0 ? (int)std::lround((r.x1 - r.x0) / tile) : 1;
  int nz = tile > 0 ? (int)std::lround((r.z1 - r.z0) / tile) : 1;
  for (int i = 0; i < nx; i++) {
    for (int k = 0; k < nz; k++) {
      Rect t = {r.x0 + (r.x1 - r.x0) * i / nx, r.x0 + (r.x1 - r.x0) * (i + 1) / nx,
                r.z0 + (r.z1 - r.z0) * k / nz, r.z0 + (r.z1 - r.z0) * (k + 1) / nz, r.y};
      float c[4][3];
      corners(t, z_sign, c);
      for (int v : {0, 1, 2, 0, 2, 3}) out.insert(out.end(), c[v], c[v] + 3);
    }
  }
  return out;
}

// What an engine knows about a decal and hands to zshift: its nearest and farthest eye
// distance and the eye-space tilt |dz/dx| + |dz/dy| of its plane, from the view matrix
// `view` (column-major, as glLoadMatrixf takes it; OSG and Irrlicht store theirs this way).
// `forward` is the sign of eye z in front of the camera: -1 for OpenGL's right-handed eye
// space, +1 for a left-handed one.
struct DecalExtent {
  double nearest, farthest, slope;
};
inline DecalExtent decal_extent(const double view[16], const float corner[4][3], double forward) {
  DecalExtent e = {INFINITY, 0.0, 0.0};
  for (int i = 0; i < 4; i++) {
    const float *p = corner[i];
    double z = view[2] * p[0] + view[6] * p[1] + view[10] * p[2] + view[14];
    double d = forward * z;
    e.nearest = std::fmin(e.nearest, d);
    e.farthest = std::fmax(e.farthest, d);
  }
  // The world normal (0, 1, 0) in eye space is the view matrix's second column.
  double nx = view[4], ny = view[5], nz = view[6];
  e.slope = (std::fabs(nx) + std::fabs(ny)) / std::fabs(nz);
  std::printf("decal at eye distance %.3f to %.3f, plane slope %.3f\n", e.nearest, e.farthest,
              e.slope);
  return e;
}

// How far in front of the ground the occluder is, as zshift's bleed gap is measured: the
// smallest difference of eye depth (along the view axis) between the occluder and the ground
// behind it on one line of sight, over a fine grid of the occluder's points.
inline double occluder_gap(const View &v) {
  Axes a = axes(v);
  const Rect &o = kOccluder;
  double gap = INFINITY;
  for (int i = 0; i <= 40; i++) {
    for (int k = 0; k <= 40; k++) {
      double p[3] = {o.x0 + (o.x1 - o.x0) * i / 40, o.y, o.z0 + (o.z1 - o.z0) * k / 40};
      double dir[3] = {p[0] - v.eye[0], p[1] - v.eye[1], p[2] - v.eye[2]};
      normalize(dir);
      double along = o.y / -dir[1]; // from the occluder down the line of sight to y = 0
      double axial = dir[0] * a.forward[0] + dir[1] * a.forward[1] + dir[2] * a.forward[2];
      gap = std::fmin(gap, along * axial);
    }
  }
  return gap;
}

// The format of an unsigned normalized depth buffer of `bits` bits (16, 24 or 32).
inline ZshiftFormat unorm_format(int bits) {
  return bits == 16 ? ZSHIFT_FORMAT_UNORM16 : bits == 24 ? ZSHIFT_FORMAT_UNORM24 : ZSHIFT_FORMAT_UNORM32;
}

// What the engine knows about its ground, for zshift: 0 when the rasterizer clips nothing of it,
// else the largest |x|, |y| or |z| of its eye-space vertices (`view` column-major, world
// z mirrored when z_sign < 0). The single ground quad runs behind the camera and is clipped at
// the near plane in float, which zshift must be told (ZshiftDecal::base_reach); the tiled ground
// is left at 0: its tiles are short, and the README's engine section reports what it does.
inline double ground_reach(const double view[16], double z_sign, const View &v) {
  if (v.ground_tile != 0.0) return 0.0;
  float c[4][3];
  corners(kGround, z_sign, c);
  double reach = 0.0;
  for (int i = 0; i < 4; i++) {
    for (int row = 0; row < 3; row++) {
      double e = view[row] * c[i][0] + view[4 + row] * c[i][1] + view[8 + row] * c[i][2] + view[12 + row];
      reach = std::fmax(reach, std::fabs(e));
    }
  }
  return reach;
}

// [quickstart-engines-decal]
// What the engine knows about its decal, for zshift: the viewport, the depth buffer's format and
// the rasterizer's glGetIntegerv(GL_SUBPIXEL_BITS) (queried once), the decal's nearest and
// farthest eye distance and plane tilt (decal_extent, from the view matrix), and the reach of a
// base the rasterizer clips (ground_reach; 0 for one inside the frustum).
inline ZshiftDecal describe_decal(ZshiftFormat format, int subpixel_bits, const DecalExtent &e,
                                  double base_reach = 0.0) {
  ZshiftDecal decal = {};
  decal.viewport_width = kWidth;
  decal.viewport_height = kHeight;
  decal.format = format;  // e.g. ZSHIFT_FORMAT_UNORM24 for GL_DEPTH_COMPONENT24
  decal.subpixel_bits = subpixel_bits;
  decal.decal_near = e.nearest;
  decal.decal_far = e.farthest;
  decal.slope = e.slope;  // |dz/dx| + |dz/dy| of its plane in eye space
  decal.exact_depth = 0;  // its corners are not the ground's
  decal.base_reach = base_reach;  // the ground crosses the near plane: the clipper's float error
  return decal;
}
// [/quickstart-engines-decal]

// zshift's bleed gap for the decal drawn over a base drawn with `m` (column-major, as the GPU
// gets it) under `clip`: occluders nearer than the ground by at least this eye depth are never
// overdrawn (ZshiftRecommendation::bleed_gap). NaN, with zshift's reason printed, if zshift
// refuses.
inline double bleed_gap(const float m[16], ZshiftClip clip, const ZshiftDecal &decal) {
  ZshiftRecommendation rec;
  if (zshift_recommend_for_matrix(m, clip, &decal, &rec) != ZSHIFT_OK) {
    std::fprintf(stderr, "zshift_recommend_for_matrix: %s\n", zshift_last_error());
    return NAN;
  }
  return rec.bleed_gap;
}

// Prints the elements in which zshift's matrix differs from the engine's (one, 10 or 14).
inline void print_changed(const float engine[16], const float zshift[16]) {
  for (int i = 0; i < 16; i++)
    if (engine[i] != zshift[i])
      std::printf("element %d: camera %.9g, zshift %.9g\n", i, engine[i], zshift[i]);
}

// An RGBA8 picture, rows bottom-up as glReadPixels returns them.
struct Picture {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;
  const unsigned char *at(int x, int y) const { return &rgba[4 * ((size_t)y * width + x)]; }
};

enum Color { kBlack, kBlue, kRed, kYellow, kOther };
inline Color classify(const unsigned char *p) {
  if (p[0] == 0 && p[1] == 0 && p[2] == 0) return kBlack;
  if (p[0] == 0 && p[1] == 0 && p[2] == 255) return kBlue;
  if (p[0] == 255 && p[1] == 0 && p[2] == 0) return kRed;
  if (p[0] == 255 && p[1] == 255 && p[2] == 0) return kYellow;
  return kOther;
}

struct Tally {
  int footprint = 0; // decal pixels the occluder does not cover
  int lost = 0;      // ... that the scene does not show
  int covered = 0;   // decal pixels behind the occluder
  int bled = 0;      // ... where the scene shows the decal instead
  int stray = 0;     // pixels of none of the scene's colours, or decal outside its footprint
};

inline Tally tally(const Picture &scene, const Picture &decal, const Picture &occluder) {
  Tally t;
  for (int y = 0; y < scene.height; y++) {
    for (int x = 0; x < scene.width; x++) {
      Color s = classify(scene.at(x, y));
      bool in_decal = classify(decal.at(x, y)) == kRed;
      bool behind = classify(occluder.at(x, y)) == kYellow;
      if (s == kOther || (s == kRed && !in_decal)) t.stray++;
      if (in_decal && !behind) {
        t.footprint++;
        if (s != kRed) t.lost++;
      } else if (in_decal) {
        t.covered++;
        if (s == kRed) t.bled++;
      }
    }
  }
  return t;
}

inline void print_tally(const char *engine, const char *method, const Tally &t) {
  std::printf("%-20s %-21s decal %5d px, lost %5d; behind occluder %4d px, bled %4d; stray %d\n",
              engine, method, t.footprint, t.lost, t.covered, t.bled, t.stray);
}

// The control's matrix: the engine's `m` with the decal lifted toward the camera by twice the
// occluder's gap at the decal's nearest point (zshift_offset_matrix; the lift grows with
// distance, under every convention), so that it shows through the occluder: the bleed check
// can fail in this scene. False, with zshift's reason printed, if zshift refuses.
inline bool control_matrix(const float m[16], ZshiftClip clip, double gap, const DecalExtent &e,
                           float out[16]) {
  if (zshift_offset_matrix(m, clip, 2.0 * gap, e.nearest, out) != ZSHIFT_OK) {
    std::fprintf(stderr, "zshift_offset_matrix: %s\n", zshift_last_error());
    return false;
  }
  return true;
}

// The verdict: the pictures are sound, the scene z-fights without an offset, zshift's matrix
// loses no decal pixel and lets none bleed through the occluder, and the control (`over`, the
// decal lifted by twice the occluder's gap) does bleed. Prints why not.
// When the occluder lies within zshift's bleed gap (`occluder_gap` < `bleed_gap`: a depth buffer
// too coarse to keep the occluder in front of a lifted decal), the contract allows bleeding and
// neither bleed check applies; the counts are printed all the same.
inline int verdict(const char *engine, const Tally &none, const Tally &zshift, const Tally &over,
                   double occluder_gap, double bleed_gap) {
  int failed = 0;
  bool bleed_checked = occluder_gap >= bleed_gap;
  std::printf("%s: occluder %.4f in front of the ground, zshift's bleed gap %.4f: %s\n", engine,
              occluder_gap, bleed_gap,
              bleed_checked ? "must not bleed" : "within the gap, bleeding allowed");
  if (!(bleed_gap > 0.0)) {
    std::fprintf(stderr, "FAIL %s: no bleed gap from zshift\n", engine);
    failed = 1;
  }
  if (none.footprint < 1000 || none.covered < 100 || zshift.footprint != none.footprint) {
    std::fprintf(stderr, "FAIL %s: the decal covers %d/%d pixels, the occluder %d: not the scene\n",
                 engine, none.footprint, zshift.footprint, none.covered);
    failed = 1;
  }
  if (none.stray != 0 || zshift.stray != 0) {
    std::fprintf(stderr, "FAIL %s: %d/%d pixels show none of the scene's colours\n", engine,
                 none.stray, zshift.stray);
    failed = 1;
  }
  if (none.lost == 0) {
    std::fprintf(stderr, "FAIL %s: with no offset no decal pixel was lost: no z-fighting\n", engine);
    failed = 1;
  }
  if (zshift.lost != 0 || (bleed_checked && zshift.bled != 0)) {
    std::fprintf(stderr, "FAIL %s: with zshift's matrix %d decal pixels were lost, %d bled\n",
                 engine, zshift.lost, zshift.bled);
    failed = 1;
  }
  if (bleed_checked && over.bled == 0) {
    std::fprintf(stderr, "FAIL %s: even a decal lifted by twice the occluder's gap does not bleed "
                 "through it: the bleed check proves nothing\n", engine);
    failed = 1;
  }
  if (!failed) std::printf("%s: ok\n", engine);
  return failed;
}

// The command line of every engine example:
// [--depth 16|24|32 | --reversed] [--subpixel-bits B] [OUTPUT_DIR].
const int kAskGL = -2; // subpixel_bits: what glGetIntegerv(GL_SUBPIXEL_BITS) reports
struct Options {
  int depth_bits = kDepthBits; // for engines that let the program choose the depth buffer
  bool reversed = false;       // reversed Z: [0, 1] clip depth, GL_GREATER, float depth buffer
  int subpixel_bits = kAskGL;  // -1 is ZSHIFT_SUBPIXEL_UNSNAPPED
  std::string out_dir;         // where the pictures go; none when empty
};

// Parses the command line and checks that there is an X display to open; prints why not.
inline bool parse_options(int argc, char **argv, Options &o) {
  for (int i = 1; i < argc; i++) {
    std::string a = argv[i];
    if (a == "--depth" && i + 1 < argc) o.depth_bits = std::atoi(argv[++i]);
    else if (a == "--subpixel-bits" && i + 1 < argc) o.subpixel_bits = std::atoi(argv[++i]);
    else if (a == "--reversed") o.reversed = true;
    else if (a.rfind("--", 0) != 0) o.out_dir = a;
    else {
      std::fprintf(stderr, "usage: %s [--depth 16|24|32 | --reversed] [--subpixel-bits B] [OUTPUT_DIR]\n",
                   argv[0]);
      return false;
    }
  }
  if (o.depth_bits != 16 && o.depth_bits != 24 && o.depth_bits != 32) {
    std::fprintf(stderr, "FAIL: --depth %d: 16, 24 or 32 bits\n", o.depth_bits);
    return false;
  }
  if (!std::getenv("DISPLAY")) {
    std::fprintf(stderr, "FAIL: no X display (DISPLAY is unset): run under xvfb-run -a -s "
                         "'-screen 0 1024x768x24'\n");
    return false;
  }
  return true;
}

// Checks the depth buffer a context reports (glGetIntegerv(GL_DEPTH_BITS)).
inline bool known_depth_bits(int bits) {
  if (bits == 16 || bits == 24 || bits == 32) return true;
  std::fprintf(stderr, "FAIL: the framebuffer has %d depth bits, not 16, 24 or 32\n", bits);
  return false;
}

// The decal's projection in a frame: the camera's own, zshift's, or the control's.
enum Method { kNoOffset, kZshift, kControl };

// What `compare` needs from an engine: each a few lines of the engine's own API.
struct Engine {
  std::string name;                  // e.g. "OSG D24 grazing"
  double occluder_gap = 0.0;         // occluder_gap(view)
  double bleed_gap = 0.0;            // zshift's, for this view's decal
  const char *depth_test;            // the engine's: "GL_LESS", "GL_LEQUAL" or "GL_GREATER"
  const char *ties_test = "";        // the same with ties to the decal, for decal_ties
  std::function<void(bool)> show_base;  // the ground and the occluder
  std::function<void(bool)> show_decal;
  std::function<void(Method)> decal_projection;
  std::function<void(bool)> decal_ties; // ties_test for the decal; empty if already the default
  std::function<bool(Picture &, const std::string &png)> shoot; // draw, read back, save if named
};

// Renders the frames, counts the pixels, prints the table and returns the verdict (0: passed).
inline int compare(const Engine &e, const std::string &out_dir, const std::string &tag) {
  auto file = [&](const char *name) { return out_dir.empty() ? "" : out_dir + "/" + tag + name; };
  Picture occluder, scene_none, scene_ties, decal_none, scene_zshift, decal_zshift, scene_over,
      decal_over;
  bool ok = true;
  e.show_base(true);
  e.show_decal(false);
  ok = ok && e.shoot(occluder, "");
  e.show_decal(true);
  e.decal_projection(kNoOffset);
  ok = ok && e.shoot(scene_none, file("none.png"));
  if (e.decal_ties) {
    e.decal_ties(true); // ties go to the decal: what is left is the rounding noise
    ok = ok && e.shoot(scene_ties, file("none_ties.png"));
    e.decal_ties(false);
  }
  e.show_base(false);
  ok = ok && e.shoot(decal_none, "");
  e.decal_projection(kZshift);
  ok = ok && e.shoot(decal_zshift, "");
  e.decal_projection(kControl);
  ok = ok && e.shoot(decal_over, "");
  e.show_base(true);
  ok = ok && e.shoot(scene_over, file("control.png"));
  e.decal_projection(kZshift);
  ok = ok && e.shoot(scene_zshift, file("zshift.png"));
  if (!ok) return 1;

  const char *engine = e.name.c_str();
  Tally none = tally(scene_none, decal_none, occluder);
  Tally zshift = tally(scene_zshift, decal_zshift, occluder);
  Tally over = tally(scene_over, decal_over, occluder);
  print_tally(engine, (std::string("no offset, ") + e.depth_test).c_str(), none);
  if (e.decal_ties) {
    Tally ties = tally(scene_ties, decal_none, occluder);
    print_tally(engine, (std::string("no offset, ") + e.ties_test).c_str(), ties);
  }
  print_tally(engine, "zshift", zshift);
  print_tally(engine, "control: lifted 2x gap", over);
  return verdict(engine, none, zshift, over, e.occluder_gap, e.bleed_gap);
}

} // namespace decal_scene

#endif // ZSHIFT_ENGINES_DECAL_SCENE_H
