"""zshift from Python with moderngl on a headless EGL context: a decal on a floor at 45°.

Draws a blue floor and a smaller red decal in the same plane (eye-space z = -500 - y), base first,
depth test GL_LESS, 24-bit depth, through a GL 3.3 shader whose projection comes from zshift. Once
with the plain frustum (the decal z-fights) and once with zshift.recommend_matrix (the offset
zshift's error model of the rasterizer recommends); counts the decal pixels the floor hides and
exits nonzero with a message unless the plain decal loses some and zshift's loses none.

    PYTHONPATH=bindings/python python3 bindings/python/examples/decal_moderngl.py

Needs moderngl (pip install moderngl) and Mesa's EGL. Conventions as zshift's: OpenGL
right-handed eye space, NDC depth [-1, 1], column-major matrices.
"""

import struct
import sys

import moderngl

import zshift

SIZE = 256
N, F, HALF = 0.1, 1e6, 0.05  # glFrustum(-HALF, HALF, -HALF, HALF, N, F)
Z0, SLOPE = -500.0, -1.0  # the plane z = Z0 + SLOPE * y

VERTEX = """
#version 330 core
uniform mat4 projection;
in vec3 eye;
void main() { gl_Position = projection * vec4(eye, 1.0); }
"""
FRAGMENT = """
#version 330 core
uniform vec4 color;
out vec4 frag;
void main() { frag = color; }
"""


def quad(w, y0, y1):
    """Two triangles on the plane, x in [-w, w], y in [y0, y1], as packed floats."""
    corners = [(-w, y0), (w, y0), (w, y1), (-w, y0), (w, y1), (-w, y1)]
    return struct.pack("18f", *(v for x, y in corners for v in (x, y, Z0 + SLOPE * y)))


RED, BLUE = (1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0)


def render(ctx, program, draws):
    """Clears, draws each (vertices, projection, color) in order, returns RGB pixels as pixel triples."""
    ctx.clear(0.0, 0.0, 0.0, 1.0, depth=1.0)
    for vertices, projection, color in draws:
        program["projection"].write(struct.pack("16f", *projection))  # column-major, as zshift gives it
        program["color"].value = color
        ctx.vertex_array(program, [(ctx.buffer(vertices), "3f", "eye")]).render(moderngl.TRIANGLES)
    data = ctx.fbo.read(components=3)
    return [data[i : i + 3] for i in range(0, len(data), 3)]


def is_red(pixel):
    return pixel == b"\xff\x00\x00"


def main():
    ctx = moderngl.create_context(standalone=True, backend="egl", require=330)
    fbo = ctx.framebuffer(ctx.renderbuffer((SIZE, SIZE)), ctx.depth_renderbuffer((SIZE, SIZE)))
    fbo.use()
    ctx.enable(moderngl.DEPTH_TEST)
    ctx.depth_func = "<"
    program = ctx.program(vertex_shader=VERTEX, fragment_shader=FRAGMENT)
    d = -Z0
    floor, decal = quad(0.45 * d, -0.3 * d, 0.35 * d), quad(0.2 * d, -0.15 * d, 0.15 * d)

    plain = zshift.frustum(-HALF, HALF, -HALF, HALF, N, F)
    # What the engine knows about the decal: its depth range on the plane, the plane's slope, and
    # the rasterizer's sub-pixel precision (snapping assumed: the conservative case).
    depths = sorted(-(Z0 + SLOPE * y) for y in (-0.15 * d, 0.15 * d))
    scene = dict(frustum=(-HALF, HALF, -HALF, HALF, N, F), viewport=(SIZE, SIZE),
                 depth_format=zshift.GL_DEPTH_COMPONENT24, decal_depths=depths, slope=abs(SLOPE),
                 subpixel_bits=ctx.info["GL_SUBPIXEL_BITS"])
    shifted = zshift.recommend_matrix(**scene)
    epsilon = zshift.recommend(**scene).epsilon
    mask = [is_red(p) for p in render(ctx, program, [(decal, plain, RED)])]  # the decal alone
    total = sum(mask)
    lost = {}
    for name, projection in (("plain", plain), ("zshift", shifted)):
        pixels = render(ctx, program, [(floor, plain, BLUE), (decal, projection, RED)])
        lost[name] = sum(1 for m, p in zip(mask, pixels) if m and not is_red(p))
    lost_plain, lost_zshift = lost["plain"], lost["zshift"]
    print(f"{ctx.info['GL_RENDERER']}: {total} decal pixels; lost without offset {lost_plain}, "
          f"with zshift's recommendation (epsilon {epsilon:.4g}) {lost_zshift}")
    if total == 0 or lost_plain == 0:
        sys.exit("FAIL: the scene does not z-fight without an offset (or shows no decal)")
    if lost_zshift != 0:
        sys.exit(f"FAIL: zshift's decal lost {lost_zshift} pixels")


if __name__ == "__main__":
    main()
