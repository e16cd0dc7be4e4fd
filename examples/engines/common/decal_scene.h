// The decal scene every engine example draws, and the check of its pixels.
//
// A large ground plane (blue) seen at a grazing angle from eye height, a decal (red) lying on it,
// and a thin slab (yellow) floating a few centimetres above part of the decal. World space is
// y-up and right-handed (OpenGL's); an engine with a left-handed world (Irrlicht) mirrors z.
// The depth buffer has 24 bits, the depth test is the engine's default (GL_LESS or GL_LEQUAL).
//
// Each engine renders these frames per method (`compare` below) and reads each back with its
// own screenshot call:
//   scene     base, occluder, then the decal (the picture a user sees)
//   decal     the decal alone (where its pixels are: the reference footprint)
//   occluder  base and occluder without the decal, once (where the occluder covers)
// and, as a control, the scene with kControlScale times zshift's offset, which must bleed.
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

namespace decal_scene {

const int kWidth = 640;
const int kHeight = 480;
const double kFovyDegrees = 45.0;
const double kNear = 0.1;
const double kFar = 1000.0;
const int kDepthBits = 24;

// The camera: eye height 3, looking at the ground 30 units ahead (5.7 degrees below horizontal).
const double kEye[3] = {0.0, 3.0, 0.0};
const double kTarget[3] = {0.0, 0.0, -30.0};

// Axis-aligned rectangles in a plane y = const: x0, x1, z0, z1, y.
struct Rect {
  double x0, x1, z0, z1, y;
};
const Rect kGround = {-500.0, 500.0, -500.0, 500.0, 0.0};
const Rect kDecal = {-3.0, 3.0, -40.0, -20.0, 0.0};
const Rect kOccluder = {0.0, 4.0, -34.0, -28.0, 0.05};

// The corners of a rectangle, counter-clockwise seen from above, as two triangles (0 1 2, 0 2 3).
inline void corners(const Rect &r, double z_sign, float out[4][3]) {
  const double xz[4][2] = {{r.x0, r.z1}, {r.x1, r.z1}, {r.x1, r.z0}, {r.x0, r.z0}};
  for (int i = 0; i < 4; i++) {
    out[i][0] = (float)xz[i][0];
    out[i][1] = (float)r.y;
    out[i][2] = (float)(z_sign * xz[i][1]);
  }
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
  return e;
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
  std::printf("%-10s %-21s decal %5d px, lost %5d; behind occluder %4d px, bled %4d; stray %d\n",
              engine, method, t.footprint, t.lost, t.covered, t.bled, t.stray);
}

// How many times zshift's offset the control draws with: enough to push the decal through
// the occluder, which proves the bleed check can fail in this scene.
const double kControlScale = 100.0;

// The verdict: the pictures are sound, the scene z-fights without an offset, zshift's matrix
// loses no decal pixel and lets none bleed through the occluder, and the control (`over`,
// kControlScale times zshift's offset) does bleed. Prints why not.
inline int verdict(const char *engine, const Tally &none, const Tally &zshift, const Tally &over) {
  int failed = 0;
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
  if (zshift.lost != 0 || zshift.bled != 0) {
    std::fprintf(stderr, "FAIL %s: with zshift's matrix %d decal pixels were lost, %d bled\n",
                 engine, zshift.lost, zshift.bled);
    failed = 1;
  }
  if (over.bled == 0) {
    std::fprintf(stderr, "FAIL %s: even %g times zshift's offset does not bleed through the "
                 "occluder: the bleed check proves nothing\n", engine, kControlScale);
    failed = 1;
  }
  if (!failed) std::printf("%s: ok\n", engine);
  return failed;
}

// The command line of every engine example: [--depth 16|24|32] [--subpixel-bits B] [OUTPUT_DIR].
const int kAskGL = -2; // subpixel_bits: what glGetIntegerv(GL_SUBPIXEL_BITS) reports
struct Options {
  int depth_bits = kDepthBits; // for engines that let the program choose the depth buffer
  int subpixel_bits = kAskGL;  // -1 is ZSHIFT_SUBPIXEL_UNSNAPPED
  std::string out_dir;         // where the pictures go; none when empty
};

// Parses the command line and checks that there is an X display to open; prints why not.
inline bool parse_options(int argc, char **argv, Options &o) {
  for (int i = 1; i < argc; i++) {
    std::string a = argv[i];
    if (a == "--depth" && i + 1 < argc) o.depth_bits = std::atoi(argv[++i]);
    else if (a == "--subpixel-bits" && i + 1 < argc) o.subpixel_bits = std::atoi(argv[++i]);
    else if (a.rfind("--", 0) != 0) o.out_dir = a;
    else {
      std::fprintf(stderr, "usage: %s [--depth 16|24|32] [--subpixel-bits B] [OUTPUT_DIR]\n", argv[0]);
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

// The decal's projection in a frame: the camera's own, zshift's, or the control.
enum Method { kNoOffset, kZshift, kControl };

// What `compare` needs from an engine: each a few lines of the engine's own API.
struct Engine {
  std::string name;                  // e.g. "OSG D24"
  const char *depth_test;            // the engine's default: "GL_LESS" or "GL_LEQUAL"
  std::function<void(bool)> show_base;  // the ground and the occluder
  std::function<void(bool)> show_decal;
  std::function<void(Method)> decal_projection;
  std::function<void(bool)> decal_lequal; // GL_LEQUAL for the decal; empty if already the default
  std::function<bool(Picture &, const std::string &png)> shoot; // draw, read back, save if named
};

// Renders the frames, counts the pixels, prints the table and returns the verdict (0: passed).
inline int compare(const Engine &e, const std::string &out_dir, const std::string &tag) {
  auto file = [&](const char *name) { return out_dir.empty() ? "" : out_dir + "/" + tag + name; };
  Picture occluder, scene_none, scene_lequal, decal_none, scene_zshift, decal_zshift, scene_over,
      decal_over;
  bool ok = true;
  e.show_base(true);
  e.show_decal(false);
  ok = ok && e.shoot(occluder, "");
  e.show_decal(true);
  e.decal_projection(kNoOffset);
  ok = ok && e.shoot(scene_none, file("none.png"));
  if (e.decal_lequal) {
    e.decal_lequal(true); // ties go to the decal: what is left is the rounding noise
    ok = ok && e.shoot(scene_lequal, file("none_lequal.png"));
    e.decal_lequal(false);
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
  if (e.decal_lequal) {
    Tally lequal = tally(scene_lequal, decal_none, occluder);
    print_tally(engine, "no offset, GL_LEQUAL", lequal);
  }
  print_tally(engine, "zshift", zshift);
  print_tally(engine, ("control: " + std::to_string((int)kControlScale) + "x zshift").c_str(), over);
  return verdict(engine, none, zshift, over);
}

} // namespace decal_scene

#endif // ZSHIFT_ENGINES_DECAL_SCENE_H
