"""zshift for Python: depth offsets through the projection matrix, and exact depth precision.

A thin ctypes layer over zshift's C ABI (``include/zshift.h``); no compiled extension. The library
is found as :mod:`zshift._library` describes (``ZSHIFT_LIBRARY`` first, then the copy ``pip install``
put inside this package, then ``target/release``, then ``target/debug``, then the system path) on
the first call.

Conventions, as in the C header: OpenGL right-handed eye space looking down -z, NDC depth
[-1, 1], window depth [0, 1]; ``n``, ``f``, ``d`` are positive distances (``f`` may be
``math.inf`` where a function says so), ``pz`` is an eye-space z (negative in front of the
camera); ``delta > 0`` moves geometry toward the camera and gives ``epsilon < 0``. Matrices are
16 floats in column-major order (what ``glLoadMatrixf`` takes; element 10 is row 2, column 2):
a tuple of Python floats, or a ``numpy.float32`` array of shape (16,) when numpy is installed.
Scalars are Python floats. Every failure raises :class:`ZshiftError` carrying the C status and
the library's message for it. Equation numbers refer to the texts zshift implements: Lengyel's
offset matrix ("4.1.x"), Walker's depth resolution, Kooima's median projection.
"""

import collections as _collections
import ctypes as _ctypes
import enum as _enum_module
import functools as _functools
import math as _math

from . import _library
from ._library import LibraryNotFound

try:
    import numpy as _numpy
except ImportError:  # numpy is optional: matrices are then tuples
    _numpy = None

__all__ = [
    "ABI_VERSION", "Status", "ZshiftError", "LibraryNotFound", "frustum", "load_offset_matrix",
    "epsilon", "min_epsilon", "min_delta_toward", "max_delta_away", "window_depth",
    "depth_resolution", "recommend", "recommend_matrix", "Recommendation", "SUBPIXEL_UNSNAPPED",
    "GL_DEPTH_COMPONENT16", "GL_DEPTH_COMPONENT24", "GL_DEPTH_COMPONENT32", "GL_DEPTH_COMPONENT32F",
    "Clip", "Format", "DepthTest", "BiasApi", "OffsetKind", "last_error", "MIN_INFINITE_TWEAK", "RangeOffset", "perspective", "projection",
    "offset_projection", "offset_perspective", "tweaked_infinite", "offset_tweaked_infinite",
    "median_ndc_offset", "window_depth_clip", "depth_step", "median_depth_step", "min_ndc_offset",
    "min_epsilon_clip", "min_relative_epsilon", "bias_of_shift", "shift_of_bias", "tight_planes",
    "range_offset", "recommend_clip", "recommend_clip_matrix",
    "status_message", "version", "library_path",
    "offset_matrix", "offset_matrix_ndc", "decal_matrix", "recommend_for_matrix", "decal_matrix_planes",
    "recommend_for_planes", "ortho", "offset_ortho",
    "ortho_depth_step",
    "probe", "profile_worst_case", "Profile", "NEAR_CLIP_CLIPPED_F32", "NEAR_CLIP_PLANE_PRESERVING",
    "clip_to_frustum", "shadow_bias", "shadow_bias_receivers", "ShadowBias", "Light", "Lookup",
]

#: The version of the C ABI these bindings were written for (``ZSHIFT_ABI_VERSION``).
ABI_VERSION = 5

#: ``subpixel_bits`` for a rasterizer that sets depth up from unsnapped positions (Mesa llvmpipe).
#: Never a default: the recommendation functions require ``subpixel_bits`` (the rasterizer's
#: ``glGetIntegerv(GL_SUBPIXEL_BITS)``, 0 being the most conservative value) unless a ``profile``
#: from :func:`probe` supplies it.
SUBPIXEL_UNSNAPPED = -1

#: The depth formats :func:`recommend` knows, as GL internal format enums.
GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT32 = 0x81A5, 0x81A6, 0x81A7
GL_DEPTH_COMPONENT32F = 0x8CAC

#: What :func:`recommend` returns: the C ``ZshiftRecommendation``'s fields, as floats.
Recommendation = _collections.namedtuple("Recommendation", [name for name, _ in _library.ZshiftRecommendation._fields_])


class Status(_enum_module.IntEnum):
    """The C status codes (``ZSHIFT_OK``, ``ZSHIFT_ERR_*``)."""

    OK = 0
    NULL_POINTER = 1
    NOT_FINITE = 2
    DOMAIN = 3
    UNRESOLVABLE = 4
    OVERFLOW = 5
    INTERNAL = 6
    GL = 7


class ZshiftError(ValueError):
    """A zshift call failed. ``status`` says how (a :class:`Status`, or the raw code if unknown);
    ``message`` (also ``str(error)``) says which input, its value and why: the library's
    ``zshift_last_error()`` detail, such as ``"the near plane distance n must be greater than 0
    (n = -1)"``, or the status's sentence where there is none."""

    def __init__(self, status, detail=""):
        try:
            status = Status(status)
        except ValueError:
            pass
        self.status = status
        self.message = detail or status_message(status)
        super().__init__(self.message)


@_functools.lru_cache(maxsize=None)
def _loaded():
    return _library.load()


def _lib():
    return _loaded()[0]


def library_path():
    """The path of the shared library in use (loading it if needed)."""
    return _loaded()[1]


def status_message(status):
    """The library's sentence for a status code (never fails; unknown codes get
    ``"unknown zshift status"``)."""
    return _lib().zshift_status_message(int(status)).decode("utf-8")


def last_error():
    """The detail of the last failed zshift call on this thread (``""`` after a success); the
    same text a :class:`ZshiftError` carries."""
    return _last_error()


def version():
    """The library's version string, such as ``"0.1.0"``."""
    return _lib().zshift_version().decode("utf-8")


def _last_error():
    lib = _lib()
    fn = lib.zshift_last_error
    fn.argtypes, fn.restype = [], _ctypes.c_char_p
    return fn().decode("utf-8", "replace")


def _check(status):
    if status != Status.OK:
        raise ZshiftError(status, _last_error())


def _bits(bits):
    # ctypes would wrap an out-of-range int into uint32 silently (2**32 + 24 -> 24).
    if not isinstance(bits, int) or not 0 <= bits < 2**32:
        raise ZshiftError(Status.DOMAIN, f"the depth buffer bits must be an integer in 1..=32 (bits = {bits!r})")
    return bits


def _matrix(call):
    out = (_ctypes.c_float * 16)()
    _check(call(out))
    if _numpy is not None:
        return _numpy.array(out, dtype=_numpy.float32)
    return tuple(out)


def _scalar(call):
    out = _ctypes.c_double()
    _check(call(_ctypes.byref(out)))
    return out.value


def frustum(l, r, b, t, n, f):
    """The ``glFrustum(l, r, b, t, n, f)`` matrix (seed 000, eq. 4.1.1), each element the float32
    nearest the exact value. ``f`` may be ``math.inf`` (element 10 is -1, element 14 is -2n).

    Raises :class:`ZshiftError`: ``NOT_FINITE`` for NaN or a stray infinity; ``DOMAIN`` if
    ``l == r``, ``b == t``, ``n <= 0`` or ``f <= n``; ``OVERFLOW`` if an element exceeds float32.
    """
    return _matrix(lambda out: _lib().zshift_frustum(l, r, b, t, n, f, out))


def load_offset_matrix(l, r, b, t, n, f, delta, pz):
    """The drop-in for the seed's ``LoadOffsetMatrix``: :func:`frustum` with element 10 scaled by
    ``1 + epsilon(n, f, delta, pz)`` (eq. 4.1.3 and 4.1.7), rounded away from the plain element so
    the offset is never lost to float32 rounding. Every other element equals :func:`frustum`'s.

    Raises :class:`ZshiftError`: as :func:`frustum`; ``NOT_FINITE`` for a NaN or infinite
    ``delta`` or ``pz``; ``DOMAIN`` if ``pz`` is outside [-f, -n] or ``pz + delta >= 0``.
    """
    return _matrix(lambda out: _lib().zshift_load_offset_matrix(l, r, b, t, n, f, delta, pz, out))


def epsilon(n, f, delta, pz):
    """Epsilon for an eye-space shift ``delta`` at eye depth ``pz`` (eq. 4.1.7):
    ``-(2fn/(f+n)) * delta / (pz * (pz + delta))``.

    Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` (bad planes, ``pz`` outside [-f, -n],
    ``pz + delta >= 0``); ``OVERFLOW``.
    """
    return _scalar(lambda out: _lib().zshift_epsilon(n, f, delta, pz, out))


def min_epsilon(n, f, bits):
    """The smallest ``|epsilon|`` that moves depth by one step of a ``bits``-bit buffer:
    ``2/(2^bits - 1) * (f - n)/(f + n)`` (eq. 4.1.8 as corrected by seed 002).

    Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` (bad planes, ``bits`` outside 1..32).
    """
    return _scalar(lambda out: _lib().zshift_min_epsilon(n, f, _bits(bits), out))


def min_delta_toward(n, f, bits, pz):
    """The smallest shift toward the camera that changes the stored depth at ``pz``:
    ``k*pz^2/(1 - k*pz)``, eq. 4.1.9 with seed 002's ``k = (f - n)/(f*n*(2^bits - 1))``.

    Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` (bad planes, ``pz`` outside [-f, -n],
    ``bits`` outside 1..32).
    """
    return _scalar(lambda out: _lib().zshift_min_delta_toward(n, f, _bits(bits), pz, out))


def max_delta_away(n, f, bits, pz):
    """The largest (least negative) shift away from the camera that still changes the stored
    depth at ``pz``: ``-k*pz^2/(1 + k*pz)``, eq. 4.1.10 with the corrected k.

    Raises :class:`ZshiftError`: as :func:`min_delta_toward`; ``UNRESOLVABLE`` if
    ``k*|pz| >= 1``; ``OVERFLOW``.
    """
    return _scalar(lambda out: _lib().zshift_max_delta_away(n, f, _bits(bits), pz, out))


def window_depth(n, f, d):
    """The window depth in [0, 1] of a point at eye distance ``d`` (Walker's f(d), seed 001).

    Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` (bad planes, ``d`` outside [n, f]).
    """
    return _scalar(lambda out: _lib().zshift_window_depth(n, f, d, out))


def depth_resolution(n, f, bits, d):
    """The exact depth step at eye distance ``d``: ``q*d^2/(b + q*d)`` with ``q = 1/(2^bits - 1)``
    and ``b = fn/(f - n)`` (Walker's eq. 3, seed 001).

    Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` (bad planes, ``d`` outside [n, f],
    ``bits`` outside 1..32).
    """
    return _scalar(lambda out: _lib().zshift_depth_resolution(n, f, _bits(bits), d, out))


def _corner_fields(decal_depths, slope, corners):
    """``(near, far, slope, pointer, count, keepalive)``: with ``corners`` (eye-space ``(x, y, z)``
    triples) the C record gets them and zeros for the fields they replace; ``decal_depths`` must
    then be ``None`` and ``slope`` 0."""
    if corners is None:
        if decal_depths is None:
            raise TypeError("pass decal_depths=(nearest, farthest) (the decal's eye distances) or corners=")
        near, far = decal_depths
        return near, far, slope, None, 0, None
    if decal_depths is not None or slope != 0.0:
        raise ZshiftError(Status.DOMAIN, "with corners, pass decal_depths=None and slope=0: the corners define the decal")
    flat = [float(c) for corner in corners for c in corner]
    if len(flat) % 3:
        raise TypeError("corners must be (x, y, z) triples")
    array = (_ctypes.c_float * max(len(flat), 1))(*flat)
    return 0.0, 0.0, 0.0, _ctypes.cast(array, _ctypes.c_void_p), len(flat) // 3, array


def _subpixel_bits(subpixel_bits, profile):
    """``subpixel_bits`` as the C record takes it. It has no default (the C header: 0 is the most
    conservative value, "not a default"); a ``profile`` supplies the rasterizer's snapping, and
    its own ``subpixel_bits`` then fills the (ignored) field."""
    if subpixel_bits is not None:
        return subpixel_bits
    if profile is not None and isinstance(profile, Profile):
        return profile.subpixel_bits
    raise TypeError(
        "subpixel_bits is required (it has no default): pass glGetIntegerv(GL_SUBPIXEL_BITS) "
        "(0 is the most conservative value), zshift.SUBPIXEL_UNSNAPPED (-1) for a rasterizer that "
        "sets depth up from unsnapped positions such as Mesa llvmpipe, or profile=zshift.probe(...)")


def _attach_corners(record, pointer, count, keepalive):
    record.decal_corners = pointer
    record.decal_corner_count = count
    record._corners_keepalive = keepalive


def _scene(frustum, viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits,
           profile=None, base_reach=0.0, corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    l, r, b, t, n, f = frustum
    width, height = viewport
    near, far, slope, pointer, count, keepalive = _corner_fields(decal_depths, slope, corners)
    subpixel_bits = _subpixel_bits(subpixel_bits, profile)
    depth_format = _enum(depth_format, Format, "depth_format") & 0xFFFFFFFF
    for name, value, low, high in (
        ("viewport width", width, 0, 2**32), ("viewport height", height, 0, 2**32),
        ("subpixel_bits", subpixel_bits, -(2**31), 2**31),
    ):
        # ctypes would wrap out-of-range integers silently.
        if not isinstance(value, int) or not low <= value < high:
            raise ZshiftError(Status.DOMAIN, f"the {name} must be an integer in [{low}, {high}) ({name} = {value!r})")
    scene = _library.ZshiftScene(l, r, b, t, n, f, width, height, depth_format, near, far, slope,
                                 1 if exact_depth else 0, subpixel_bits)
    scene.base_reach = base_reach
    _attach_pipeline(scene, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    _attach_profile(scene, profile)
    _attach_corners(scene, pointer, count, keepalive)
    return scene


def _attach_pipeline(record, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box):
    """Fills the fields the C records share for the engine's pipeline: ``depth_func`` (a
    :class:`DepthTest`, its name or GL enum; ``None``: the convention's strict test),
    ``viewport_x``/``viewport_y`` (``glViewport``'s origin), ``depth_range_near``/``far``
    (``glDepthRange``), ``world_reach`` (0 for eye-space vertices), ``eye_first`` (the
    shader computes ``proj * (view * p)``; ``False`` covers one view-projection applied to
    world positions, bevy's ``clip_from_world``, Unity's ``UNITY_MATRIX_VP``, with the camera's
    view and a box as for a model-view multiplied in double, at 6-12 times the bleed gap of an
    eye-first shader, median), and ``view_matrix`` with ``world_box`` (the shader's view matrix, 16 floats column-major, and the world-space box
    ``((min x, min y, min z), (max x, max y, max z))`` of the base and decal: for a
    tessellated ground, of the cells the decal touches, the only base triangles under it; base
    and decal both drawn through that matrix. A model with a matrix of its own (a decal entity,
    a terrain chunk): the camera's view and a box holding its world corners (for a model
    centred on its origin) when its model-view is multiplied in double and rounded once to
    float32; multiplied in float32, pass ``world_reach`` instead)."""
    record.depth_func = 0 if depth_test is None else _enum(depth_test, DepthTest, "depth_test") & 0xFFFFFFFF
    _attach_framebuffer(record.pipeline, viewport_origin, depth_range)
    record.pipeline.world_reach = world_reach
    record.pipeline.eye_first = 1 if eye_first else 0
    _attach_view(record, view_matrix, world_box)


def _attach_framebuffer(pipeline, viewport_origin, depth_range):
    """Fills a ``ZshiftPipeline``'s framebuffer state: ``viewport_x``/``viewport_y`` from
    ``viewport_origin`` (``glViewport``'s origin, integers) and ``depth_range_near``/``far`` from
    ``depth_range`` (``glDepthRange``)."""
    x, y = viewport_origin
    for name, value in (("viewport_origin x", x), ("viewport_origin y", y)):
        if not isinstance(value, int) or not 0 <= value < 2**32:
            raise ZshiftError(Status.DOMAIN, f"the {name} must be an integer in [0, 2**32) ({name} = {value!r})")
    pipeline.viewport_x, pipeline.viewport_y = x, y
    pipeline.depth_range_near, pipeline.depth_range_far = depth_range


def _attach_view(record, view_matrix, world_box):
    """Points ``record.pipeline.view_matrix`` at a C copy of ``view_matrix`` (kept alive by the
    record) and fills ``world_box``; both ``None`` leaves them NULL and zero."""
    if (view_matrix is None) != (world_box is None):
        raise TypeError("view_matrix and world_box go together: pass both (16 floats, and "
                        "((min x, min y, min z), (max x, max y, max z))) or neither")
    if view_matrix is not None:
        view = _engine_matrix(view_matrix)
        (x0, y0, z0), (x1, y1, z1) = world_box
        record.pipeline.world_box = (_ctypes.c_double * 6)(x0, y0, z0, x1, y1, z1)
        record._view_keepalive = view
        record.pipeline.view_matrix = _ctypes.cast(view, _ctypes.c_void_p)


def _attach_profile(record, profile):
    """Points ``record.profile`` at a C copy of ``profile`` (a :data:`Profile` from :func:`probe`
    or :func:`profile_worst_case`), kept alive by the record; ``None`` leaves it NULL."""
    if profile is None:
        return
    if not isinstance(profile, Profile):
        raise TypeError(f"profile must be a zshift.Profile (from zshift.probe), not {type(profile).__name__}")
    c_profile = _ZshiftProfile()
    for name, ctype in _ZshiftProfile._fields_:
        value = getattr(profile, name)
        setattr(c_profile, name, ctype(*value) if isinstance(value, tuple) else value)
    record._profile_keepalive = c_profile
    record.profile = _ctypes.cast(_ctypes.pointer(c_profile), _ctypes.c_void_p)


def recommend(frustum, viewport, depth_format, decal_depths=None, slope=0.0, exact_depth=False,
              subpixel_bits=None, profile=None, base_reach=0.0, corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    """The smallest offset zshift's error model of a real rasterizer guarantees ends z-fighting
    between a decal and its coplanar base (quantum, f32 rounding of transform, vertices and
    interpolation, sub-pixel snapping; seeds 000, 002, 004), as a :data:`Recommendation`.

    ``frustum`` is the base's ``(l, r, b, t, n, f)`` (``f`` may be ``math.inf``); ``viewport`` the
    ``(width, height)`` in pixels; ``depth_format`` a GL internal format (``GL_DEPTH_COMPONENT24``
    ...); ``decal_depths`` the decal's ``(nearest, farthest)`` eye distance; ``slope`` its plane's
    eye-space ``|dz/dx| + |dz/dy|``; ``exact_depth`` whether base and decal corners share one float
    z (facing planes only). ``subpixel_bits`` has no default, as in C: pass the rasterizer's
    ``glGetIntegerv(GL_SUBPIXEL_BITS)`` (0 is the most conservative value),
    :data:`SUBPIXEL_UNSNAPPED` for a rasterizer that sets depth up from unsnapped positions
    (Mesa llvmpipe), or a ``profile``, which supplies it; omitting both raises ``TypeError``.
    Use ``delta_at_far`` with :func:`load_offset_matrix` at ``pz = -farthest``, or
    :func:`recommend_matrix`.

    ``profile`` is the rasterizer's :data:`Profile` from :func:`probe` (call it once per context
    and pass it to every recommendation); ``None`` is the worst case with ``subpixel_bits``. A
    profile supplies every rasterizer fact, its snapping included, so ``subpixel_bits`` is then
    ignored. ``base_reach`` is 0 for a base inside the frustum, else the largest ``|x|``,
    ``|y|``, ``|z|`` of its eye-space vertices (a floor running behind the camera, which the
    rasterizer clips: the offset gains the clipping term). ``corners`` are the decal's eye-space
    ``(x, y, z)`` corners (3 to 64, in any order: the decal is taken as their convex hull): with them pass ``decal_depths=None`` and ``slope=0``; the
    corners give the depths, the slope and where the decal lies on the screen, which makes the
    offset far tighter on sloped planes; a decal under the camera may reach behind it, and one
    may run on beyond the far plane (the part drawn counts). The other recommendation functions take these keywords alike.

    Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` (bad frustum, zero viewport, unknown
    format, decal depths outside [n, f] or decreasing, negative slope, ``exact_depth`` with a
    slope, ``subpixel_bits`` < -1 or > 32); ``OVERFLOW``.
    """
    scene = _scene(frustum, viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits, profile,
                   base_reach, corners, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    out = _library.ZshiftRecommendation()
    _check(_lib().zshift_recommend(_ctypes.byref(scene), _ctypes.byref(out)))
    return Recommendation(*(getattr(out, name) for name in Recommendation._fields))


def recommend_matrix(frustum, viewport, depth_format, decal_depths=None, slope=0.0, exact_depth=False,
                     subpixel_bits=None, profile=None, base_reach=0.0, corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    """The decal's projection for :func:`recommend`'s offset: :func:`frustum` with element 10
    scaled by ``1 + epsilon`` and rounded outward. Arguments and errors as :func:`recommend`."""
    scene = _scene(frustum, viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits, profile,
                   base_reach, corners, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    return _matrix(lambda out: _lib().zshift_recommend_matrix(_ctypes.byref(scene), out))


# ---- Every clip convention, Kooima's median projection, depth bias, planning ----


class Clip(_enum_module.IntEnum):
    """NDC depth convention (``ZSHIFT_CLIP_*``): OpenGL's [-1, 1]; [0, 1] (glClipControl
    ZERO_TO_ONE, Direct3D, Vulkan); reversed [0, 1] (near 1, far 0, GL_GREATER; float depth)."""

    NEG_ONE_TO_ONE = 0
    ZERO_TO_ONE = 1
    REVERSED_ZERO_TO_ONE = 2


class Format(_enum_module.IntEnum):
    """Depth attachment format (``ZSHIFT_FORMAT_*``)."""

    UNORM16 = 0x81A5  # the GL enums: GL_DEPTH_COMPONENT16, 24, 32, 32F
    UNORM24 = 0x81A6
    UNORM32 = 0x81A7
    FLOAT32 = 0x8CAC
    UNORM24_STENCIL8 = 0x88F0  # GL_DEPTH24_STENCIL8: depth stored as UNORM24
    FLOAT32_STENCIL8 = 0x8CAD  # GL_DEPTH32F_STENCIL8: depth stored as FLOAT32


class BiasApi(_enum_module.IntEnum):
    """Whose constant depth bias (``ZSHIFT_BIAS_*``): glPolygonOffset units, Direct3D DepthBias,
    Vulkan depthBiasConstantFactor."""

    OPENGL = 0
    DIRECT3D = 1
    VULKAN = 2


class OffsetKind(_enum_module.IntEnum):
    """What :func:`range_offset` returns (``ZSHIFT_OFFSET_*``): a signed NDC offset for element 10,
    or a relative epsilon for element 14 (reversed Z with float depth)."""

    NDC = 0
    RELATIVE = 1


#: The smallest tweak for :func:`tweaked_infinite` that keeps far geometry inside the clip volume
#: in float arithmetic: 2^-22 (Lengyel, GDC 2007).
MIN_INFINITE_TWEAK = 2.0**-22

#: What :func:`range_offset` returns: the offset and the eye-space shifts it makes at lo and hi.
RangeOffset = _collections.namedtuple("RangeOffset", ["offset", "shift_at_lo", "shift_at_hi"])


class DepthTest(_enum_module.IntEnum):
    """The depth test of a pass (``ZSHIFT_DEPTH_TEST_*``), by its GL _enum_module."""

    LESS = 0x0201
    LEQUAL = 0x0203
    GREATER = 0x0204
    GEQUAL = 0x0206


_ARGUMENT_NAMES = {"Clip": "clip", "Format": "format", "BiasApi": "api", "OffsetKind": "kind",
                   "DepthTest": "depth_test", "Light": "light", "Lookup": "lookup"}


def _enum(value, kind, name=None):
    # One enum per kind of argument, as the C header has one type per kind: a member of another
    # enum (a Format passed as a Clip) is a TypeError, never a silently different call. A
    # member's name is accepted as a string ("ZERO_TO_ONE", any case). A plain int is passed as
    # is (the library refuses an unknown value and says which field and value).
    name = name or _ARGUMENT_NAMES.get(kind.__name__, kind.__name__)
    members = ", ".join(f"{kind.__name__}.{member.name}" for member in kind)
    if isinstance(value, _enum_module.Enum) and not isinstance(value, kind):
        raise TypeError(f"{name} must be a zshift.{kind.__name__} (one of {members}), not {value!r}")
    if isinstance(value, str):
        member = kind.__members__.get(value.upper())
        if member is None:
            raise ZshiftError(Status.DOMAIN, f"{name} = {value!r} is not a zshift.{kind.__name__}: "
                                             f"pass one of {members}, or its name")
        value = member
    # An int32 for the C call; ctypes would wrap a larger int silently.
    if isinstance(value, bool) or not isinstance(value, int) or not -(2**31) <= value < 2**32:
        raise ZshiftError(Status.DOMAIN, f"{name} = {value!r} is not a zshift.{kind.__name__}: "
                                         f"pass one of {members}, or its name")
    return int(value) if value < 2**31 else int(value) - 2**32


def perspective(fovy, aspect, n, f):
    """``gluPerspective(fovy, aspect, n, f)``, fovy in degrees, NDC depth [-1, 1]; ``f`` may be
    ``math.inf``. Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` unless 0 < fovy < 180,
    aspect > 0, 0 < n < f."""
    return _matrix(lambda out: _lib().zshift_perspective(fovy, aspect, n, f, out))


def projection(l, r, b, t, n, f, clip):
    """glFrustum's x/y rows with the depth row of ``clip`` (a :class:`Clip`).
    Raises :class:`ZshiftError`: as :func:`frustum`; ``DOMAIN`` for an unknown clip."""
    return _matrix(lambda out: _lib().zshift_projection(l, r, b, t, n, f, _enum(clip, Clip), out))


def offset_projection(l, r, b, t, n, f, clip, delta, pz):
    """:func:`projection` with geometry at ``pz`` moved toward the camera by ``delta``: a constant
    NDC offset through element 10 ([-1, 1], [0, 1]; seed 000 eq. 4.1.3-4.1.7 generalised) or
    element 14 scaled (reversed), rounded outward. Raises :class:`ZshiftError`: as
    :func:`projection`; ``DOMAIN`` if pz is outside [-f, -n] or the shifted point leaves [n, f]."""
    return _matrix(lambda out: _lib().zshift_offset_projection(l, r, b, t, n, f, _enum(clip, Clip), delta, pz, out))


def offset_perspective(fovy, aspect, n, f, clip, delta, pz):
    """:func:`offset_projection` for gluPerspective parameters. Errors as both."""
    return _matrix(lambda out: _lib().zshift_offset_perspective(fovy, aspect, n, f, _enum(clip, Clip), delta, pz, out))


def tweaked_infinite(l, r, b, t, n, tweak):
    """The tweaked infinite projection: m10 = tweak - 1, m14 = (tweak - 2) n, NDC [-1, 1].
    Raises :class:`ZshiftError`: as :func:`frustum`; ``DOMAIN`` unless 0 <= tweak < 1."""
    return _matrix(lambda out: _lib().zshift_tweaked_infinite(l, r, b, t, n, tweak, out))


def offset_tweaked_infinite(l, r, b, t, n, tweak, delta, pz):
    """:func:`tweaked_infinite` with geometry at ``pz`` moved toward the camera by ``delta``
    (element 10, rounded outward). Raises :class:`ZshiftError`: as :func:`tweaked_infinite`;
    ``DOMAIN`` if pz or pz + delta > -n."""
    return _matrix(lambda out: _lib().zshift_offset_tweaked_infinite(l, r, b, t, n, tweak, delta, pz, out))


def median_ndc_offset(median, delta, pz):
    """The ``ndc_offset`` uniform of bindings/glsl/ftransform_mdp.glsl (Kooima's median
    projection, seed 003) that moves geometry at ``pz`` toward the camera by ``delta``.
    Raises :class:`ZshiftError`: ``NOT_FINITE``; ``DOMAIN`` unless median > 0, pz <= 0 and
    pz + delta <= 0."""
    return _scalar(lambda out: _lib().zshift_median_ndc_offset(median, delta, pz, out))


def window_depth_clip(n, f, clip, d):
    """The window depth at eye distance ``d`` under ``clip`` (Walker's f(d), seed 001; reversed
    n(f - d)/((f - n)d)). Raises :class:`ZshiftError`: ``NOT_FINITE``, ``DOMAIN``."""
    return _scalar(lambda out: _lib().zshift_window_depth_clip(n, f, _enum(clip, Clip), d, out))


def depth_step(n, f, clip, format, d):
    """The exact depth step at eye distance ``d`` under ``clip`` and ``format`` (a :class:`Format`;
    Walker's eq. 3 for every convention). Raises :class:`ZshiftError`: ``NOT_FINITE``, ``DOMAIN``."""
    return _scalar(lambda out: _lib().zshift_depth_step(n, f, _enum(clip, Clip), _enum(format, Format), d, out))


def median_depth_step(median, format, d):
    """The depth step at eye distance ``d`` (>= 0) under Kooima's median projection (seed 003).
    Raises :class:`ZshiftError`: ``NOT_FINITE``, ``DOMAIN``."""
    return _scalar(lambda out: _lib().zshift_median_depth_step(median, _enum(format, Format), d, out))


def min_ndc_offset(n, f, clip, format, d):
    """The smallest constant NDC offset (a magnitude) that changes the stored depth at ``d``
    (seed 002's 2/(2^m - 1) for UNORM under [-1, 1]). Raises :class:`ZshiftError`: as
    :func:`depth_step`."""
    return _scalar(lambda out: _lib().zshift_min_ndc_offset(n, f, _enum(clip, Clip), _enum(format, Format), d, out))


def min_epsilon_clip(n, f, clip, format, d):
    """The smallest |epsilon| for element 10's scaling that changes the stored depth at ``d``
    (eq. 4.1.8 as corrected by seed 002 under [-1, 1]). Raises :class:`ZshiftError`: as
    :func:`depth_step`; ``UNRESOLVABLE`` for reversed Z with ``f = math.inf``."""
    return _scalar(lambda out: _lib().zshift_min_epsilon_clip(n, f, _enum(clip, Clip), _enum(format, Format), d, out))


def min_relative_epsilon(n, f, clip, format, d):
    """The smallest relative epsilon (element 14 scaled by 1 + epsilon) that changes the stored
    depth at ``d``. Raises :class:`ZshiftError`: as :func:`depth_step`."""
    return _scalar(lambda out: _lib().zshift_min_relative_epsilon(n, f, _enum(clip, Clip), _enum(format, Format), d, out))


def bias_of_shift(n, f, clip, format, api, delta, pz):
    """The constant depth bias of ``api`` (a :class:`BiasApi`) equivalent to moving geometry at
    ``pz`` toward the camera by ``delta`` (negative under [-1, 1] and [0, 1]).
    Raises :class:`ZshiftError`: ``NOT_FINITE``, ``DOMAIN``."""
    return _scalar(lambda out: _lib().zshift_bias_of_shift(n, f, _enum(clip, Clip), _enum(format, Format), _enum(api, BiasApi), delta, pz, out))


def shift_of_bias(n, f, clip, format, api, bias, pz):
    """The eye-space shift toward the camera that a constant ``bias`` of ``api`` makes at ``pz``
    (the inverse of :func:`bias_of_shift`). Raises :class:`ZshiftError`: as
    :func:`bias_of_shift`; ``UNRESOLVABLE``."""
    return _scalar(lambda out: _lib().zshift_shift_of_bias(n, f, _enum(clip, Clip), _enum(format, Format), _enum(api, BiasApi), bias, pz, out))


def tight_planes(nearest, farthest):
    """The tightest clip planes ``(n, f)`` for a scene between eye distances ``nearest`` and
    ``farthest`` (``f`` may be ``math.inf``). Raises :class:`ZshiftError`: ``NOT_FINITE``;
    ``DOMAIN`` unless 0 < nearest <= farthest."""
    out = (_ctypes.c_double * 2)()
    _check(_lib().zshift_tight_planes(nearest, farthest, out))
    return tuple(out)


def range_offset(n, f, clip, format, kind, lo, hi, steps):
    """The smallest single offset that moves stored depth by at least ``steps`` steps at every
    distance in [lo, hi], as a :data:`RangeOffset`; multiply ``offset`` by k for the k-th stacked
    decal layer. Raises :class:`ZshiftError`: ``NOT_FINITE``, ``DOMAIN``, ``UNRESOLVABLE``."""
    out = (_ctypes.c_double * 3)()
    _check(_lib().zshift_range_offset(n, f, _enum(clip, Clip), _enum(format, Format), _enum(kind, OffsetKind), lo, hi, steps, out))
    return RangeOffset(*out)


# ---- The recommendation per clip convention ----


def recommend_clip(frustum, viewport, depth_format, decal_depths, clip, slope=0.0, exact_depth=False,
                   subpixel_bits=None, profile=None, base_reach=0.0, corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    """:func:`recommend` for a scene drawn under ``clip`` (a :class:`Clip`), as a
    :data:`Recommendation` (``zshift_recommend_clip``). ``Clip.NEG_ONE_TO_ONE`` gives
    :func:`recommend`; ``Clip.ZERO_TO_ONE`` (glClipControl GL_ZERO_TO_ONE, GL_LESS) a constant NDC
    offset through element 10 (``epsilon`` < 0 is Lengyel's element-10 form); reversed Z
    (GL_GREATER, clear depth 0) a relative ``epsilon`` > 0 for element 14, ``window_offset`` its
    value at the farthest decal depth, no glPolygonOffset equivalent (0, 0). Use
    :func:`recommend_clip_matrix` for the decal's matrix.

    Raises :class:`ZshiftError`: as :func:`recommend`; ``DOMAIN`` for an unknown clip.
    """
    scene = _scene(frustum, viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits, profile,
                   base_reach, corners, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    out = _library.ZshiftRecommendation()
    _check(_lib().zshift_recommend_clip(_ctypes.byref(scene), _enum(clip, Clip), _ctypes.byref(out)))
    return Recommendation(*(getattr(out, name) for name in Recommendation._fields))


def recommend_clip_matrix(frustum, viewport, depth_format, decal_depths, clip, slope=0.0, exact_depth=False,
                          subpixel_bits=None, profile=None, base_reach=0.0, corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    """The decal's projection for :func:`recommend_clip`'s offset: :func:`projection` under
    ``clip`` with element 10 lowered ([-1, 1], [0, 1]) or element 14 scaled by ``1 + epsilon``
    (reversed), rounded outward. Arguments and errors as :func:`recommend_clip`."""
    scene = _scene(frustum, viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits, profile,
                   base_reach, corners, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    return _matrix(lambda out: _lib().zshift_recommend_clip_matrix(_ctypes.byref(scene), _enum(clip, Clip), out))


def clip_to_frustum(frustum, polygon, world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    """Cuts a convex base polygon to the view frustum ``(l, r, b, t, n, f)`` of ``glFrustum``
    (``zshift_clip_to_frustum``), in double and slightly inside, so that the rasterizer clips
    nothing of it: draw the result as a triangle fan and pass ``base_reach=0``. A ground that runs
    behind the camera, drawn raw, makes the recommendation carry the large clipping term (or be
    refused, ``UNRESOLVABLE``, "cut the base to the frustum"); cut this way it carries none.

    ``polygon`` is a sequence of eye-space ``(x, y, z)`` vertices in order around the polygon;
    returns the cut polygon as a list of ``(x, y, z)`` tuples (empty when nothing is inside).

    Stored in world space (``world_reach``, or ``view_matrix`` with ``world_box``, and
    ``eye_first``, as for :func:`recommend`: ``zshift_clip_to_frustum_stored``), the cut lies
    further inside by the largest error that storage and the float32 view transform can give a
    vertex, an error relative to the world coordinates, not to the vertex's distance from the
    camera: cut only 2**-16 inside, a vertex close to the camera can land outside, and a
    rasterizer that clips at the screen's sides (Mesa's llvmpipe) cuts a sliver off its
    triangle whose pixel can be off by half a pixel of depth gradient. Camera-relative
    rendering needs none of it.

    Raises :class:`ZshiftError`: ``NOT_FINITE`` for a NaN or infinite coordinate or frustum
    parameter (except ``f = math.inf``); ``DOMAIN`` for a bad frustum, more than 65536 vertices
    or a negative ``world_reach``; ``TypeError`` for a vertex that is not an ``(x, y, z)``
    triple, or ``view_matrix`` without ``world_box`` (or the reverse).
    """
    l, r, b, t, n, f = frustum
    vertices = [tuple(float(c) for c in vertex) for vertex in polygon]
    if any(len(vertex) != 3 for vertex in vertices):
        raise TypeError("polygon must be a sequence of (x, y, z) eye-space vertices")
    count = len(vertices)
    capacity = count + 6  # the header: count + 6 always suffices
    flat = (_ctypes.c_double * max(3 * count, 1))(*[c for vertex in vertices for c in vertex])
    out = (_ctypes.c_double * (3 * capacity))()
    out_count = _ctypes.c_uint32()
    if count > 65536:
        raise ZshiftError(Status.DOMAIN, f"the polygon must have at most 65536 vertices (count = {count})")
    tail = [_ctypes.POINTER(_ctypes.c_double), _ctypes.c_uint32, _ctypes.POINTER(_ctypes.c_double),
            _ctypes.c_uint32, _ctypes.POINTER(_ctypes.c_uint32)]
    args = (flat, count, out, capacity, _ctypes.byref(out_count))
    if world_reach == 0.0 and view_matrix is None and world_box is None:
        fn = _lib().zshift_clip_to_frustum
        fn.argtypes = [_ctypes.c_double] * 6 + tail
        fn.restype = _ctypes.c_int32
        _check(fn(l, r, b, t, n, f, *args))
    else:
        holder = _StoredPipeline()
        holder.pipeline.world_reach = world_reach
        holder.pipeline.eye_first = 1 if eye_first else 0
        _attach_view(holder, view_matrix, world_box)
        fn = _lib().zshift_clip_to_frustum_stored
        fn.argtypes = [_ctypes.c_double] * 6 + [_ctypes.POINTER(_library.ZshiftPipeline)] + tail
        fn.restype = _ctypes.c_int32
        _check(fn(l, r, b, t, n, f, _ctypes.byref(holder.pipeline), *args))
    return [(out[3 * i], out[3 * i + 1], out[3 * i + 2]) for i in range(out_count.value)]


class _StoredPipeline:
    """A ``ZshiftPipeline`` with what keeps its view matrix alive (:func:`_attach_view`)."""

    def __init__(self):
        self.pipeline = _library.ZshiftPipeline()


# ---- The front door: the engine's own matrix in, the decal's matrix out ----


class _Decal(_ctypes.Structure):
    """The C ``ZshiftDecal`` (include/zshift.h), field for field."""

    _fields_ = [
        ("viewport_width", _ctypes.c_uint32), ("viewport_height", _ctypes.c_uint32),
        ("format", _ctypes.c_uint32), ("subpixel_bits", _ctypes.c_int32),
        ("decal_near", _ctypes.c_double), ("decal_far", _ctypes.c_double), ("slope", _ctypes.c_double),
        ("exact_depth", _ctypes.c_uint32),
        ("base_reach", _ctypes.c_double),
        ("profile", _ctypes.c_void_p),  # const ZshiftProfile *, NULL for the worst case
        ("decal_corners", _ctypes.c_void_p), ("decal_corner_count", _ctypes.c_uint32),  # const float *
        ("depth_func", _ctypes.c_uint32),  # 0: the convention's strict test
        ("pipeline", _library.ZshiftPipeline),
    ]


_FLOAT16 = _ctypes.c_float * 16


def _front_door():
    """The library, with the front door's signatures declared (the argument types are structs of
    one 32-bit integer, passed as that integer)."""
    lib = _lib()
    if not getattr(lib, "_zshift_front_door", False):
        d, i32, status = _ctypes.c_double, _ctypes.c_int32, _ctypes.c_int32
        matrix, float_out = _ctypes.POINTER(_ctypes.c_float), _ctypes.POINTER(_ctypes.c_float)
        decal, record = _ctypes.POINTER(_Decal), _ctypes.POINTER(_library.ZshiftRecommendation)
        for name, argtypes in {
            "zshift_offset_matrix": [matrix, i32, d, d, float_out],
            "zshift_offset_matrix_ndc": [matrix, i32, d, float_out],
            "zshift_decal_matrix": [matrix, i32, decal, float_out],
            "zshift_recommend_for_matrix": [matrix, i32, decal, record],
            "zshift_decal_matrix_planes": [matrix, i32, decal, _ctypes.c_uint32, float_out],
            "zshift_recommend_for_planes": [matrix, i32, decal, _ctypes.c_uint32, record],
            "zshift_ortho": [d] * 6 + [i32, float_out],
            "zshift_offset_ortho": [d] * 6 + [i32, d, float_out],
            "zshift_ortho_depth_step": [d, d, i32, i32, d, _ctypes.POINTER(_ctypes.c_double)],
        }.items():
            fn = getattr(lib, name)
            fn.argtypes, fn.restype = argtypes, status
        lib._zshift_front_door = True
    return lib


def _engine_matrix(m):
    # 16 floats, column-major. A 4x4 array is refused rather than guessed: numpy's C order would
    # read a column-major matrix transposed (flatten with order="F", or pass the GL-ready array).
    shape = getattr(m, "shape", None)
    if shape is not None and tuple(shape) != (16,):
        raise TypeError(f"the matrix must be 16 floats in column-major order, not an array of shape {tuple(shape)}")
    values = list(m)
    if len(values) != 16:
        raise TypeError(f"the matrix must be 16 floats in column-major order, not {len(values)} values")
    return _FLOAT16(*values)


def _decal(viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits, profile=None, base_reach=0.0,
           corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    width, height = viewport
    near, far, slope, pointer, count, keepalive = _corner_fields(decal_depths, slope, corners)
    subpixel_bits = _subpixel_bits(subpixel_bits, profile)
    fmt = _enum(depth_format, Format, "depth_format")
    for name, value, low, high in (
        ("viewport width", width, 0, 2**32), ("viewport height", height, 0, 2**32),
        ("subpixel_bits", subpixel_bits, -(2**31), 2**31),
    ):
        if not isinstance(value, int) or not low <= value < high:
            raise ZshiftError(Status.DOMAIN, f"the {name} must be an integer in [{low}, {high}) ({name} = {value!r})")
    decal = _Decal(width, height, fmt & 0xFFFFFFFF, subpixel_bits, near, far, slope, 1 if exact_depth else 0,
                   base_reach)
    _attach_pipeline(decal, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    _attach_profile(decal, profile)
    _attach_corners(decal, pointer, count, keepalive)
    return decal


def offset_matrix(m, clip, delta, d):
    """The engine's own projection ``m`` (16 floats, column-major: what glUniformMatrix4fv takes,
    from any engine, perspective or orthographic) with geometry at eye distance ``d`` moved toward
    the camera by ``delta`` (``zshift_offset_matrix``). Only the offset element changes (10, or 14
    for reversed-Z perspective and for orthographic), rounded outward; the other 15 are
    bit-identical. ``clip`` is the :class:`Clip` ``m`` was built for: a reversed-Z matrix passed as
    ``Clip.NEG_ONE_TO_ONE`` is an error, not a wrong matrix.

    Raises :class:`ZshiftError` naming the element or input (``DOMAIN``: not a projection, a
    convention mismatch, ``d <= 0`` or ``d - delta <= 0``; ``NOT_FINITE``; ``OVERFLOW``);
    ``TypeError`` for a matrix that is not 16 values.
    """
    mat = _engine_matrix(m)
    return _matrix(lambda out: _front_door().zshift_offset_matrix(mat, _enum(clip, Clip), delta, d, out))


def offset_matrix_ndc(m, clip, ndc):
    """:func:`offset_matrix` for an NDC offset toward the camera (``zshift_offset_matrix_ndc``);
    under ``Clip.NEG_ONE_TO_ONE`` an NDC offset is twice the window-depth offset."""
    mat = _engine_matrix(m)
    return _matrix(lambda out: _front_door().zshift_offset_matrix_ndc(mat, _enum(clip, Clip), ndc, out))


def decal_matrix(m, clip, viewport, depth_format, decal_depths=None, slope=0.0, exact_depth=False,
                 subpixel_bits=None, profile=None, base_reach=0.0, corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    """The decal's matrix for the engine's own projection ``m``: the recommended offset
    (``zshift_decal_matrix``; the model of :func:`recommend_clip`, or its orthographic form) in
    ``m``'s own offset element, every other element bit-identical. The engine never restates its
    frustum. Arguments as :func:`recommend`, with ``depth_format`` a :class:`Format` (or its GL
    enum). Raises :class:`ZshiftError` naming the element or field."""
    mat = _engine_matrix(m)
    decal = _decal(viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits, profile, base_reach,
                   corners, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    return _matrix(lambda out: _front_door().zshift_decal_matrix(mat, _enum(clip, Clip), _ctypes.byref(decal), out))


def recommend_for_matrix(m, clip, viewport, depth_format, decal_depths=None, slope=0.0, exact_depth=False,
                         subpixel_bits=None, profile=None, base_reach=0.0, corners=None, depth_test=None, viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None, world_box=None):
    """The :data:`Recommendation` behind :func:`decal_matrix` (``zshift_recommend_for_matrix``)."""
    mat = _engine_matrix(m)
    decal = _decal(viewport, depth_format, decal_depths, slope, exact_depth, subpixel_bits, profile, base_reach,
                   corners, depth_test, viewport_origin, depth_range, world_reach, eye_first, view_matrix, world_box)
    out = _library.ZshiftRecommendation()
    _check(_front_door().zshift_recommend_for_matrix(mat, _enum(clip, Clip), _ctypes.byref(decal), _ctypes.byref(out)))
    return Recommendation(*(getattr(out, name) for name in Recommendation._fields))


#: The keys a plane of :func:`decal_matrix_planes` may have: what differs between the planes.
_PLANE_KEYS = ("corners", "decal_depths", "slope", "exact_depth", "base_reach", "world_box")


def _planes(viewport, depth_format, planes, subpixel_bits, profile, depth_test, viewport_origin, depth_range,
            world_reach, eye_first, view_matrix):
    """One ``ZshiftDecal`` per plane (a list that keeps each plane's corners alive), and the
    ctypes array of them."""
    planes = list(planes)
    if not planes:
        raise ZshiftError(Status.DOMAIN, "planes must hold at least one plane (count = 0)")
    decals = []
    for i, plane in enumerate(planes):
        unknown = sorted(set(plane) - set(_PLANE_KEYS))
        if unknown:
            raise TypeError(f"plane {i}: unknown key {unknown[0]!r} (a plane may have {', '.join(_PLANE_KEYS)})")
        try:
            decals.append(_decal(viewport, depth_format, plane.get("decal_depths"), plane.get("slope", 0.0),
                                 plane.get("exact_depth", False), subpixel_bits, profile, plane.get("base_reach", 0.0),
                                 plane.get("corners"), depth_test, viewport_origin, depth_range, world_reach, eye_first,
                                 view_matrix, plane.get("world_box")))
        except ZshiftError as e:
            raise ZshiftError(e.status, f"plane {i}: {e.message}") from None
    return decals, (_Decal * len(decals))(*decals)


def decal_matrix_planes(m, clip, viewport, depth_format, planes, subpixel_bits=None, profile=None, depth_test=None,
                        viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False,
                        view_matrix=None):
    """The matrix of one decal on several planes, drawn in one pass (``zshift_decal_matrix_planes``):
    a mesh decal over terrain, cut from the terrain's own triangles, each piece on its triangle's
    plane. ``planes`` is a list of dicts, one per plane, with what differs between them (the keys
    of :func:`decal_matrix`: ``corners``, or ``decal_depths`` and ``slope``; ``exact_depth``,
    ``base_reach``, ``world_box``); the other arguments are shared, as :func:`decal_matrix` takes
    them. Give each plane the corners of the base triangle its piece was cut from, not the
    piece's (a sliver's float corners do not pin its plane down), cut with
    :func:`clip_to_frustum` where the triangle reaches behind the near plane or off the screen; a plane of which nothing is drawn (wholly behind the near plane, beyond the far plane or off screen) is left out. The matrix carries the largest of the planes' offsets, which keeps every plane's pixels.
    Raises :class:`ZshiftError` whose detail begins ``plane i:`` for a plane's refusal (one
    naming ``largest_plane`` where the largest offset would move plane i past the near plane
    though its own fits: draw each piece with its own :func:`decal_matrix`, or leave out the
    piece of plane ``largest_plane``); ``TypeError`` for an unknown key."""
    mat = _engine_matrix(m)
    keep, array = _planes(viewport, depth_format, planes, subpixel_bits, profile, depth_test, viewport_origin,
                          depth_range, world_reach, eye_first, view_matrix)
    out = _matrix(lambda out: _front_door().zshift_decal_matrix_planes(mat, _enum(clip, Clip), array, len(keep), out))
    del keep
    return out


def recommend_for_planes(m, clip, viewport, depth_format, planes, subpixel_bits=None, profile=None, depth_test=None,
                         viewport_origin=(0, 0), depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False,
                         view_matrix=None):
    """The :data:`Recommendation` behind :func:`decal_matrix_planes` (``zshift_recommend_for_planes``):
    the plane with the largest offset, its ``bleed_gap`` the largest of every plane's at that offset,
    its ``polygon_offset`` the largest factor and units of the planes'."""
    mat = _engine_matrix(m)
    keep, array = _planes(viewport, depth_format, planes, subpixel_bits, profile, depth_test, viewport_origin,
                          depth_range, world_reach, eye_first, view_matrix)
    out = _library.ZshiftRecommendation()
    _check(_front_door().zshift_recommend_for_planes(mat, _enum(clip, Clip), array, len(keep), _ctypes.byref(out)))
    del keep
    return Recommendation(*(getattr(out, name) for name in Recommendation._fields))


def ortho(l, r, b, t, n, f, clip=Clip.NEG_ONE_TO_ONE):
    """``glOrtho(l, r, b, t, n, f)`` with the depth row of ``clip`` (``zshift_ortho``)."""
    return _matrix(lambda out: _front_door().zshift_ortho(l, r, b, t, n, f, _enum(clip, Clip), out))


def offset_ortho(l, r, b, t, n, f, clip, delta):
    """:func:`ortho` with every point moved toward the camera by ``delta`` (element 14, rounded
    outward; ``zshift_offset_ortho``)."""
    return _matrix(lambda out: _front_door().zshift_offset_ortho(l, r, b, t, n, f, _enum(clip, Clip), delta, out))


def ortho_depth_step(n, f, clip, format, d):
    """The exact depth step of an orthographic projection at eye distance ``d``: ``r*(f - n)``
    (``zshift_ortho_depth_step``; the same at every distance for UNORM formats)."""
    return _scalar(lambda out: _front_door().zshift_ortho_depth_step(n, f, _enum(clip, Clip), _enum(format, Format), d, out))


# ---------------------------------------------------------------------------------------------
# The rasterizer probe (zshift_probe): measures the current GL context's profile through a
# function loader. Added by the probe's owner; keep this block separate.
# ---------------------------------------------------------------------------------------------

#: ``Profile.near_clip``: primitives crossing the near plane are clipped in float (worst case).
NEAR_CLIP_CLIPPED_F32 = 1
#: ``Profile.near_clip``: a primitive crossing the near plane keeps its plane's depth.
NEAR_CLIP_PLANE_PRESERVING = 2


class _ZshiftProfile(_ctypes.Structure):
    """The C ``ZshiftProfile`` (fields documented in zshift.h)."""

    _fields_ = [
        ("measured", _ctypes.c_uint32),
        ("subpixel_bits", _ctypes.c_int32),
        ("resolvable", _ctypes.c_double * 4),
        ("plane_error", _ctypes.c_double * 4),
        ("plane_error_reversed", _ctypes.c_double),
        ("error_ulps", _ctypes.c_double),
        ("near_clip", _ctypes.c_int32),
        ("probe_seconds", _ctypes.c_double),
        ("facing_quanta", _ctypes.c_double * 4),
        ("facing_quanta_zero_to_one", _ctypes.c_double * 4),
        ("facing_reversed", _ctypes.c_double),
        ("error_ulps_reversed", _ctypes.c_double),
        ("facing_chain", _ctypes.c_int32),
        ("clip_ulps", _ctypes.c_double),
        ("line_reach", _ctypes.c_double * 2),
        ("outline_neighbour", _ctypes.c_double),
        ("line_reach_msaa", _ctypes.c_double * 2),
        ("line_reach_wide", _ctypes.c_double * 2),
        ("offset_slope", _ctypes.c_double),
        ("line_reach_msaa_whole", _ctypes.c_double * 2),
        ("line_reach_msaa_wide_whole", _ctypes.c_double * 2),
    ]


#: What :func:`probe` and :func:`profile_worst_case` return: the C ``ZshiftProfile``'s fields
#: (per-format arrays as 4-tuples in the order D16, D24, D32, D32F, line_reach, line_reach_msaa, line_reach_wide,
#: line_reach_msaa_whole and line_reach_msaa_wide_whole 2-tuples; see
#: zshift.h for each field).
Profile = _collections.namedtuple("Profile", [name for name, _ in _ZshiftProfile._fields_])

# ZshiftGlLoader: ZshiftGlProc (*)(const char *name, void *user); a function pointer travels
# as an address (c_void_p), the same size on every platform Python's ctypes supports.
_GL_LOADER = _ctypes.CFUNCTYPE(_ctypes.c_void_p, _ctypes.c_char_p, _ctypes.c_void_p)


@_functools.lru_cache(maxsize=None)
def _probe_lib():
    lib = _lib()
    lib.zshift_probe.argtypes = [_GL_LOADER, _ctypes.c_void_p, _ctypes.POINTER(_ZshiftProfile)]
    lib.zshift_probe.restype = _ctypes.c_int32
    lib.zshift_profile_worst_case.argtypes = [_ctypes.POINTER(_ZshiftProfile)]
    lib.zshift_profile_worst_case.restype = _ctypes.c_int32
    return lib


def _profile(record):
    values = []
    for name, _ in _ZshiftProfile._fields_:
        value = getattr(record, name)
        values.append(tuple(value) if isinstance(value, _ctypes.Array) else value)
    return Profile(*values)


def profile_worst_case():
    """The worst-case :class:`Profile`: the recommendation's default assumptions
    (``measured == 0``)."""
    out = _ZshiftProfile()
    _check(_probe_lib().zshift_profile_worst_case(_ctypes.byref(out)))
    return _profile(out)


def probe(get_proc_address):
    """Measures the rasterizer of the OpenGL context current on this thread (``zshift_probe``)
    and returns its :class:`Profile`. Call it once after creating the context.

    ``get_proc_address(name)`` takes an entry point's name (``str``) and returns its address as
    an ``int`` (or ``None``/0 when there is none): ``glfw.get_proc_address``, or EGL's through
    ctypes::

        egl = ctypes.CDLL("libEGL.so.1")
        egl.eglGetProcAddress.restype = ctypes.c_void_p
        egl.eglGetProcAddress.argtypes = [ctypes.c_char_p]
        profile = zshift.probe(lambda name: egl.eglGetProcAddress(name.encode()))

    Every GL state the probe touches is restored. Raises :class:`ZshiftError`: ``Status.GL``
    when the context cannot do what the probe needs (a missing entry point, no context or one
    older than 3.2, a GL error pending, a refused depth format); an exception raised by
    ``get_proc_address`` counts as "no such entry point"."""

    def loader(name, _user):
        try:
            address = get_proc_address(name.decode("ascii"))
        except Exception:  # a loader that fails finds nothing; the probe says which entry point
            return None
        return address or None

    callback = _GL_LOADER(loader)  # kept alive for the call's duration
    out = _ZshiftProfile()
    _check(_probe_lib().zshift_probe(callback, None, _ctypes.byref(out)))
    return _profile(out)


# ---- Edges over their own faces (src/lines/, docs/edges.md) ----


class EdgeMethod(_enum_module.IntEnum):
    """How edges are kept in front of their faces: ``POLYGON_OFFSET`` pushes the faces back with
    glPolygonOffset (D3D/Vulkan depth bias); ``MATRIX`` pulls the edges forward through the
    projection matrix (the one offset that moves GL_LINES)."""

    POLYGON_OFFSET = 0
    MATRIX = 1


class _Edges(_ctypes.Structure):
    """The C ``ZshiftEdges`` (include/zshift.h), field for field."""

    _fields_ = [
        ("viewport_width", _ctypes.c_uint32), ("viewport_height", _ctypes.c_uint32),
        ("format", _ctypes.c_uint32), ("subpixel_bits", _ctypes.c_int32),
        ("depth_near", _ctypes.c_double), ("depth_far", _ctypes.c_double),
        ("line_width", _ctypes.c_double), ("polygon_mode", _ctypes.c_uint32), ("samples", _ctypes.c_uint32),
        ("face_angle", _ctypes.c_double), ("face_gradient", _ctypes.c_double),
        ("hidden_separation", _ctypes.c_double),
        ("depth_func", _ctypes.c_uint32),
        ("profile", _ctypes.c_void_p),
        ("pipeline", _library.ZshiftPipeline),  # world space, viewport origin, glDepthRange
    ]


class _EdgeOffset(_ctypes.Structure):
    """The C ``ZshiftEdgeOffset``."""

    _fields_ = [
        ("matrix", _ctypes.c_float * 16), ("polygon_offset", _ctypes.c_double * 2),
        ("d3d_bias", _ctypes.c_double * 2), ("vulkan_bias", _ctypes.c_double * 2),
        ("ndc_offset", _ctypes.c_double), ("relative_epsilon", _ctypes.c_double),
        ("window_offset", _ctypes.c_double), ("line_term", _ctypes.c_double), ("line_reach", _ctypes.c_double),
        ("face_gradient", _ctypes.c_double), ("hidden_gap", _ctypes.c_double),
    ]


EdgeOffset = _collections.namedtuple("EdgeOffset", [name for name, _ in _EdgeOffset._fields_])
EdgeOffset.__doc__ = """The offset for a mesh's edges (``zshift_edge_offset``): ``matrix`` (16 floats, the edges'
projection for :attr:`EdgeMethod.MATRIX`), ``polygon_offset`` (factor, units for the faces),
``d3d_bias`` (DepthBias, SlopeScaledDepthBias), ``vulkan_bias`` (constant, slope), ``ndc_offset``,
``relative_epsilon``, ``window_offset``, ``line_term``, ``line_reach``, ``face_gradient`` and
``hidden_gap`` (eye depth behind a front face from which hidden edges never show)."""


def _edge_offset_of(out):
    """The :data:`EdgeOffset` of a filled ``_EdgeOffset``."""
    return EdgeOffset(*[tuple(getattr(out, name)) if name in ("matrix", "polygon_offset", "d3d_bias", "vulkan_bias")
                        else getattr(out, name) for name, _ in _EdgeOffset._fields_])


def _edges_lib():
    lib = _lib()
    if not getattr(lib, "_zshift_edges", False):
        matrix, edges = _ctypes.POINTER(_ctypes.c_float), _ctypes.POINTER(_Edges)
        lib.zshift_edge_offset.argtypes = [matrix, _ctypes.c_int32, edges, _ctypes.c_uint32,
                                           _ctypes.POINTER(_EdgeOffset)]
        lib.zshift_edge_planes.argtypes = [matrix, _ctypes.c_int32, edges, _ctypes.c_uint32,
                                           _ctypes.POINTER(_ctypes.c_double)]
        lib.zshift_edge_offset.restype = lib.zshift_edge_planes.restype = _ctypes.c_int32
        lib._zshift_edges = True
    return lib


def _edges(viewport, depth_format, depth_range, line_width, polygon_mode, samples, face_angle, face_gradient,
           hidden_separation, depth_test, subpixel_bits, profile, viewport_origin=(0, 0),
           framebuffer_depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None,
           world_box=None):
    width, height = viewport
    for name, value in (("viewport width", width), ("viewport height", height), ("samples", samples)):
        if not isinstance(value, int) or not 0 <= value < 2**32:
            raise ZshiftError(Status.DOMAIN, f"the {name} must be an integer in [0, 2**32) ({name} = {value!r})")
    subpixel_bits = _subpixel_bits(subpixel_bits, profile)
    record = _Edges(width, height, _enum(depth_format, Format, "depth_format") & 0xFFFFFFFF, subpixel_bits,
                    depth_range[0], depth_range[1], line_width, 1 if polygon_mode else 0, samples,
                    face_angle, face_gradient, hidden_separation,
                    0 if depth_test is None else _enum(depth_test, DepthTest, "depth_test") & 0xFFFFFFFF)
    _attach_profile(record, profile)
    _attach_framebuffer(record.pipeline, viewport_origin, framebuffer_depth_range)
    record.pipeline.world_reach = world_reach
    record.pipeline.eye_first = 1 if eye_first else 0
    _attach_view(record, view_matrix, world_box)
    return record


def edge_offset(m, clip, viewport, depth_format, depth_range, method, line_width=1.0, polygon_mode=False,
                samples=1, face_angle=0.0, face_gradient=0.0, hidden_separation=0.0, depth_test=None,
                subpixel_bits=None, profile=None, viewport_origin=(0, 0),
                framebuffer_depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None,
                world_box=None):
    """The offset that keeps a mesh's edges in front of its own faces (``zshift_edge_offset``):
    ``m`` the engine's perspective projection (16 floats, column-major) under ``clip``, the mesh
    over eye depths ``depth_range`` (nearest, farthest), ``method`` an :class:`EdgeMethod`, edges as
    GL_LINES of ``line_width`` pixels (or ``polygon_mode`` lines; a width between integers is taken as GL may
    draw it, rounded to the nearest integer, halves up, where wider: 2.5 as 3) with ``samples`` MSAA samples per
    pixel (above 1 the line reach is sqrt(2)*(w + 1)/2, or a probed profile's line_reach_msaa plus 1/16 where smaller;
    against a ``face_angle`` the line term takes at most (w + 1)/2 of the face's whole gradient), the steepest face that
    matters as ``face_angle`` (radians from the view axis: faces whose window gradient has a length up to the returned
    ``face_gradient``) or ``face_gradient`` (window depth per pixel, max(|dz/dx|, |dz/dy|); :func:`steepest_face`
    reads a mesh's own, and :func:`edge_offset_for_mesh` does both in one call), and
    ``hidden_separation`` the eye depth from which hidden edges must not show (0: no promise).
    How the engine draws the mesh (``ZshiftEdges.pipeline``): ``viewport_origin`` (``glViewport``'s
    x, y in a larger framebuffer), ``framebuffer_depth_range`` (``glDepthRange``), ``world_reach``
    (vertices in world space through a float view matrix: the largest world coordinate of the
    camera and of the mesh's origin), ``view_matrix`` with ``world_box`` (that matrix, 16 floats
    column-major, and the box of the mesh's world positions) and ``eye_first`` (the shader
    computes ``proj * (view * p)``). Returns an :data:`EdgeOffset`. Raises :class:`ZshiftError` naming the field (``UNRESOLVABLE``
    where the hidden-line gap exceeds ``hidden_separation``: see :func:`edge_planes`)."""
    mat = _engine_matrix(m)
    record = _edges(viewport, depth_format, depth_range, line_width, polygon_mode, samples, face_angle,
                    face_gradient, hidden_separation, depth_test, subpixel_bits, profile, viewport_origin,
                    framebuffer_depth_range, world_reach, eye_first, view_matrix, world_box)
    out = _EdgeOffset()
    _check(_edges_lib().zshift_edge_offset(mat, _enum(clip, Clip), _ctypes.byref(record),
                                           _enum(method, EdgeMethod, "method"), _ctypes.byref(out)))
    return _edge_offset_of(out)


def edge_planes(m, clip, viewport, depth_format, depth_range, method, line_width=1.0, polygon_mode=False,
                samples=1, face_angle=0.0, face_gradient=0.0, hidden_separation=0.0, depth_test=None,
                subpixel_bits=None, profile=None, viewport_origin=(0, 0),
                framebuffer_depth_range=(0.0, 1.0), world_reach=0.0, eye_first=False, view_matrix=None,
                world_box=None):
    """Near and far planes with which :func:`edge_offset` answers (``zshift_edge_planes``): the
    tight planes of ``depth_range``. Arguments as :func:`edge_offset`; returns ``(near, far)``."""
    mat = _engine_matrix(m)
    record = _edges(viewport, depth_format, depth_range, line_width, polygon_mode, samples, face_angle,
                    face_gradient, hidden_separation, depth_test, subpixel_bits, profile, viewport_origin,
                    framebuffer_depth_range, world_reach, eye_first, view_matrix, world_box)
    out = (_ctypes.c_double * 2)()
    _check(_edges_lib().zshift_edge_planes(mat, _enum(clip, Clip), _ctypes.byref(record),
                                           _enum(method, EdgeMethod, "method"), out))
    return (out[0], out[1])


class _Mesh(_ctypes.Structure):
    """The C ``ZshiftMesh``."""

    _fields_ = [("clip_matrix", _ctypes.POINTER(_ctypes.c_float)), ("positions", _ctypes.POINTER(_ctypes.c_float)),
                ("vertex_count", _ctypes.c_size_t), ("position_stride", _ctypes.c_size_t),
                ("indices", _ctypes.POINTER(_ctypes.c_uint32)), ("index_count", _ctypes.c_size_t)]


class _SteepestFace(_ctypes.Structure):
    """The C ``ZshiftSteepestFace``."""

    _fields_ = [("gradient", _ctypes.c_double), ("length", _ctypes.c_double), ("triangle", _ctypes.c_int64),
                ("counted", _ctypes.c_uint64), ("beyond_limit", _ctypes.c_uint64), ("culled", _ctypes.c_uint64)]


SteepestFace = _collections.namedtuple("SteepestFace", [name for name, _ in _SteepestFace._fields_])
SteepestFace.__doc__ = """A mesh's steepest face as drawn (``zshift_steepest_face``): ``gradient`` (window depth per
pixel, max(|dz/dx|, |dz/dy|): what :func:`edge_offset`'s ``face_gradient`` takes), ``length`` (the largest gradient
length, which bounds multisampled lines), ``triangle`` (the index of the face of ``gradient``, ``None`` when no face
counts), ``counted``, ``beyond_limit`` (steeper than the limit) and ``culled`` (drawing nothing)."""


def _flattened(values, name, kind):
    """``values`` as one flat list: a sequence of triples (or a numpy array of shape (N, 3)) or a flat sequence."""
    flat = []
    for item in values:
        if isinstance(item, (int, float)) or getattr(item, "shape", None) == ():
            flat.append(kind(item))
        else:
            triple = [kind(x) for x in item]
            if len(triple) != 3:
                raise TypeError(f"{name} must be triples (or a flat sequence), not items of {len(triple)} values")
            flat.extend(triple)
    return flat


def _c_array(values, name, ctype, numpy_type, kind):
    """``values`` as a ctypes array of ``ctype``: a numpy array is copied in one step (as ``numpy_type``), any other
    sequence of triples or numbers element by element."""
    if hasattr(values, "astype") and hasattr(values, "ravel"):
        flat = values.astype(numpy_type).ravel()
        return (ctype * flat.size).from_buffer_copy(flat.tobytes())
    flat = _flattened(values, name, kind)
    return (ctype * len(flat))(*flat)


def _mesh(clip_matrix, positions, indices):
    """A ``ZshiftMesh`` and the arrays it points into (keep both alive for the call)."""
    mat = _engine_matrix(clip_matrix)
    points = _c_array(positions, "positions", _ctypes.c_float, "<f4", float)
    if len(points) % 3:
        raise TypeError(f"positions must hold three floats per vertex, not {len(points)} values")
    if hasattr(indices, "min") and len(indices) and (indices.min() < 0 or indices.max() >= 2**32):
        raise ZshiftError(Status.DOMAIN, "indices must be integers in [0, 2**32)")
    if not hasattr(indices, "astype") and any(not 0 <= i < 2**32 for i in _flattened(indices, "indices", int)):
        raise ZshiftError(Status.DOMAIN, "indices must be integers in [0, 2**32)")
    index_array = _c_array(indices, "indices", _ctypes.c_uint32, "<u4", int)
    arrays = (mat, points, index_array)
    record = _Mesh(_ctypes.cast(mat, _ctypes.POINTER(_ctypes.c_float)),
                   _ctypes.cast(points, _ctypes.POINTER(_ctypes.c_float)), len(points) // 3, 0,
                   _ctypes.cast(index_array, _ctypes.POINTER(_ctypes.c_uint32)), len(index_array))
    return record, arrays


def _mesh_lib():
    lib = _edges_lib()
    if not getattr(lib, "_zshift_mesh", False):
        lib.zshift_steepest_face.argtypes = [_ctypes.POINTER(_Mesh), _ctypes.c_int32, _ctypes.c_uint32,
                                             _ctypes.c_uint32, _ctypes.c_double, _ctypes.POINTER(_SteepestFace)]
        lib.zshift_edge_offset_for_mesh.argtypes = [_ctypes.POINTER(_ctypes.c_float), _ctypes.c_int32,
                                                    _ctypes.POINTER(_Edges), _ctypes.POINTER(_Mesh), _ctypes.c_uint32,
                                                    _ctypes.POINTER(_EdgeOffset)]
        lib.zshift_steepest_face.restype = lib.zshift_edge_offset_for_mesh.restype = _ctypes.c_int32
        lib._zshift_mesh = True
    return lib


def steepest_face(clip_matrix, clip, viewport, positions, indices, limit=_math.inf):
    """The steepest face of a mesh as drawn (``zshift_steepest_face``): the largest window-depth gradient
    max(|dz/dx|, |dz/dy|) among its triangles (``indices``, three per triangle, GL_TRIANGLES order, into
    ``positions``, (x, y, z) each), drawn through ``clip_matrix`` (projection * view * model, 16 floats,
    column-major) under ``clip`` into a ``viewport`` of (width, height) pixels, and the largest gradient length,
    leaving out triangles that draw nothing and those steeper than ``limit`` (grazing: pass the ``face_gradient``
    that :func:`edge_offset` returns for a ``face_angle`` to keep every face within that angle).
    :func:`edge_offset_for_mesh` does this and the offset in one call. Returns a :data:`SteepestFace`. Raises
    :class:`ZshiftError` naming a bad input (an index past the positions, a NaN position, a zero viewport side, a
    negative limit)."""
    width, height = viewport
    for what, value in (("viewport width", width), ("viewport height", height)):
        if not isinstance(value, int) or not 0 <= value < 2**32:
            raise ZshiftError(Status.DOMAIN, f"the {what} must be an integer in [0, 2**32) ({what} = {value!r})")
    record, _keep = _mesh(clip_matrix, positions, indices)
    out = _SteepestFace()
    _check(_mesh_lib().zshift_steepest_face(_ctypes.byref(record), _enum(clip, Clip), width, height, limit,
                                            _ctypes.byref(out)))
    return SteepestFace(out.gradient, out.length, None if out.triangle < 0 else out.triangle, out.counted,
                        out.beyond_limit, out.culled)


def edge_offset_for_mesh(m, clip, viewport, depth_format, depth_range, method, clip_matrix, positions, indices,
                         **kwargs):
    """:func:`edge_offset` paying for the mesh's own steepest faces (``zshift_edge_offset_for_mesh``): ``face_angle``
    (or ``face_gradient``) is the limit beyond which faces are grazing, and the faces of the mesh within it
    (``positions`` and ``indices`` drawn through ``clip_matrix``, as :func:`steepest_face` reads them in
    ``viewport``) set the line term; every face within the limit keeps its edges. Other arguments as
    :func:`edge_offset`. Returns an :data:`EdgeOffset`; raises as :func:`edge_offset` and :func:`steepest_face`."""
    mat = _engine_matrix(m)
    args = dict(line_width=1.0, polygon_mode=False, samples=1, face_angle=0.0, face_gradient=0.0,
                hidden_separation=0.0, depth_test=None, subpixel_bits=None, profile=None)
    unknown = set(kwargs) - set(args) - {"viewport_origin", "framebuffer_depth_range", "world_reach", "eye_first",
                                         "view_matrix", "world_box"}
    if unknown:
        raise TypeError(f"edge_offset_for_mesh() got unexpected keyword arguments {sorted(unknown)}")
    args.update(kwargs)
    pipeline = {k: args.pop(k) for k in list(args) if k not in (
        "line_width", "polygon_mode", "samples", "face_angle", "face_gradient", "hidden_separation", "depth_test",
        "subpixel_bits", "profile")}
    record = _edges(viewport, depth_format, depth_range, args["line_width"], args["polygon_mode"], args["samples"],
                    args["face_angle"], args["face_gradient"], args["hidden_separation"], args["depth_test"],
                    args["subpixel_bits"], args["profile"], **pipeline)
    mesh, _keep = _mesh(clip_matrix, positions, indices)
    out = _EdgeOffset()
    _check(_mesh_lib().zshift_edge_offset_for_mesh(mat, _enum(clip, Clip), _ctypes.byref(record),
                                                   _ctypes.byref(mesh), _enum(method, EdgeMethod, "method"),
                                                   _ctypes.byref(out)))
    return _edge_offset_of(out)


__all__ += ["EdgeMethod", "EdgeOffset", "edge_offset", "edge_planes", "SteepestFace", "steepest_face",
            "edge_offset_for_mesh"]


# ---- Shadow-map bias (docs/shadows.md) ----


class Light(_enum_module.IntEnum):
    """The light's projection (``ZSHIFT_LIGHT_*``): a directional light or cascade
    (``glOrtho``), or a spot light (``glFrustum``)."""

    ORTHOGRAPHIC = 0
    PERSPECTIVE = 1


class Lookup(_enum_module.IntEnum):
    """How the lookup reads the map (``ZSHIFT_LOOKUP_*``): one texel, hardware 2x2 comparison,
    ``pcf_size`` x ``pcf_size`` PCF, or taps within ``kernel_radius`` texels."""

    NEAREST = 0
    HARDWARE_2X2 = 1
    PCF = 2
    RADIUS = 3


class _ShadowMap(_ctypes.Structure):
    """The C ``ZshiftShadowMap`` (include/zshift.h), field for field."""

    _fields_ = [
        ("light", _ctypes.c_int32),
        ("l", _ctypes.c_double), ("r", _ctypes.c_double), ("b", _ctypes.c_double),
        ("t", _ctypes.c_double), ("n", _ctypes.c_double), ("f", _ctypes.c_double),
        ("clip", _ctypes.c_int32), ("width", _ctypes.c_uint32), ("height", _ctypes.c_uint32),
        ("format", _ctypes.c_uint32), ("lookup", _ctypes.c_int32), ("pcf_size", _ctypes.c_uint32),
        ("kernel_radius", _ctypes.c_double), ("limit_angle_deg", _ctypes.c_double),
        ("receiver_near", _ctypes.c_double), ("receiver_far", _ctypes.c_double),
        ("world_reach", _ctypes.c_double), ("elevation_deg", _ctypes.c_double),
        ("profile", _ctypes.c_void_p),  # const ZshiftProfile *, NULL for the worst case
        ("pipeline", _library.ZshiftPipeline),  # the light's view matrix, world box, eye_first
    ]


class _ShadowBias(_ctypes.Structure):
    """The C ``ZshiftShadowBias``, field for field."""

    _fields_ = [(name, _ctypes.c_double) for name in (
        "reach", "quantum", "caster", "snap", "lookup", "read", "constant", "footprint",
        "slope_factor", "gl_factor", "gl_units", "gl_clamp")] + [
        ("d3d_depth_bias", _ctypes.c_int32), ("d3d_slope_scaled", _ctypes.c_float),
        ("d3d_clamp", _ctypes.c_float), ("vk_constant", _ctypes.c_float),
        ("vk_slope", _ctypes.c_float), ("vk_clamp", _ctypes.c_float),
        ("webgpu_depth_bias", _ctypes.c_int32), ("webgpu_slope_scale", _ctypes.c_float),
        ("webgpu_clamp", _ctypes.c_float)] + [(name, _ctypes.c_double) for name in (
        "along_light", "along_normal", "leak_thickness", "peter_panning")]


#: What :func:`shadow_bias` returns: the C ``ZshiftShadowBias``'s fields.
ShadowBias = _collections.namedtuple("ShadowBias", [name for name, _ in _ShadowBias._fields_])


def shadow_bias(light, projection, clip, resolution, depth_format, limit_angle_deg, receiver_depths,
                lookup=Lookup.NEAREST, pcf_size=0, kernel_radius=0.0, world_reach=0.0,
                elevation_deg=90.0, profile=None, view_matrix=None, world_box=None, eye_first=False,
                viewport_origin=(0, 0), depth_range=(0.0, 1.0)):
    """The smallest caster-side shadow bias that keeps every receiver within ``limit_angle_deg``
    of the light free of acne (``zshift_shadow_bias``), in every API's units, with the
    receiver-side alternatives and the cost; a :data:`ShadowBias`. Receivers must be planar
    across the lookup's reach: for a mesh that bends within a few texels (a sphere, a terrain)
    under a wide kernel, list its faces with :func:`shadow_bias_receivers`.

    ``light`` a :class:`Light`; ``projection`` the light's ``(l, r, b, t, n, f)``; ``clip`` a
    :class:`Clip`; ``resolution`` ``(width, height)`` in texels; ``depth_format`` a
    :class:`Format`; ``receiver_depths`` the receivers' ``(nearest, farthest)`` light-space depth
    inside ``[n, f]``; ``lookup`` a :class:`Lookup` (``pcf_size`` for ``Lookup.PCF``,
    ``kernel_radius`` for ``Lookup.RADIUS``); ``profile`` from :func:`probe` or ``None`` for the
    worst case. ``view_matrix`` (the light's view matrix the caster and lookup shaders apply to
    world positions, 16 floats column-major) with ``world_box`` (``((min x, min y, min z), (max x,
    max y, max z))`` of every caster and receiver position) replace the bound from
    ``world_reach`` by each light-space coordinate's own rounding; ``eye_first`` says both
    shaders compute ``proj * (view * p)`` (``ZshiftShadowMap.pipeline``). In a shadow atlas,
    ``viewport_origin`` is the tile's corner (the ``glViewport`` the casters are drawn with;
    ``resolution`` is the tile's size) and ``depth_range`` the ``glDepthRange`` they are drawn
    with (the lookup compares against ``near + (far - near) * depth``); units and clamp are then
    in stored depth, as the APIs apply them. Raises :class:`ZshiftError` (``Status.UNRESOLVABLE`` with the remedy when no bias
    is acne-free at that angle)."""
    record = _shadow_record(light, projection, clip, resolution, depth_format, limit_angle_deg,
                            receiver_depths, lookup, pcf_size, kernel_radius, world_reach,
                            elevation_deg, profile, view_matrix, world_box, eye_first,
                            viewport_origin, depth_range)
    lib = _lib()
    fn = lib.zshift_shadow_bias
    fn.argtypes = [_ctypes.POINTER(_ShadowMap), _ctypes.POINTER(_ShadowBias)]
    fn.restype = _ctypes.c_int32
    out = _ShadowBias()
    _check(fn(_ctypes.byref(record), _ctypes.byref(out)))
    return ShadowBias(*(getattr(out, name) for name, _ in _ShadowBias._fields_))


def _shadow_record(light, projection, clip, resolution, depth_format, limit_angle_deg, receiver_depths,
                   lookup, pcf_size, kernel_radius, world_reach, elevation_deg, profile, view_matrix,
                   world_box, eye_first, viewport_origin, depth_range):
    """A ``_ShadowMap`` from :func:`shadow_bias`'s arguments."""
    record = _ShadowMap()
    record.light = _enum(light, Light)
    record.l, record.r, record.b, record.t, record.n, record.f = projection
    record.clip = _enum(clip, Clip)
    record.width, record.height = resolution
    record.format = _enum(depth_format, Format, "depth_format") & 0xFFFFFFFF
    record.lookup = _enum(lookup, Lookup)
    if not isinstance(pcf_size, int) or not 0 <= pcf_size < 2**32:
        raise ZshiftError(Status.DOMAIN, f"pcf_size must be an integer in [0, 2**32) (pcf_size = {pcf_size!r})")
    record.pcf_size = pcf_size
    record.kernel_radius = kernel_radius
    record.limit_angle_deg = limit_angle_deg
    record.receiver_near, record.receiver_far = receiver_depths
    record.world_reach = world_reach
    record.elevation_deg = elevation_deg
    _attach_profile(record, profile)
    record.pipeline.eye_first = 1 if eye_first else 0
    _attach_framebuffer(record.pipeline, viewport_origin, depth_range)
    _attach_view(record, view_matrix, world_box)
    return record


def shadow_bias_receivers(light, projection, clip, resolution, depth_format, receivers,
                          limit_angle_deg=89.9, lookup=Lookup.NEAREST, pcf_size=0, kernel_radius=0.0,
                          world_reach=0.0, elevation_deg=90.0, profile=None, view_matrix=None,
                          world_box=None, eye_first=False, viewport_origin=(0, 0),
                          depth_range=(0.0, 1.0)):
    """:func:`shadow_bias` for the receivers an engine lists (``zshift_shadow_bias_receivers``):
    ``receivers`` a sequence of planar polygons, each a sequence of 3 to 64 ``(x, y, z)`` corners
    in the light's view space (a spot light at the origin, looking down -z), counter-clockwise
    seen from the lit front, inside the light's frustum. The bias follows from each receiver's
    own plane, at any angle short of edge-on, also where a kernel reads across from one receiver
    to another (a mesh's faces may be listed); receivers facing away by more than
    ``limit_angle_deg`` everywhere are skipped (under a spot light, the angle to the ray from the
    light to each point, not to its axis); ``view_matrix``, ``world_box`` and ``eye_first`` as
    for :func:`shadow_bias` (with ``eye_first``, only the error off each receiver's plane counts),
    and ``viewport_origin`` and ``depth_range`` (an atlas tile) as for :func:`shadow_bias`.
    Raises :class:`ZshiftError` as :func:`shadow_bias` does (``Status.DOMAIN`` naming a bad receiver)."""
    polygons = [list(polygon) for polygon in receivers]
    record = _shadow_record(light, projection, clip, resolution, depth_format, limit_angle_deg,
                            (projection[4], projection[5]), lookup, pcf_size, kernel_radius,
                            world_reach, elevation_deg, profile, view_matrix, world_box, eye_first,
                            viewport_origin, depth_range)
    flat = [float(x) for polygon in polygons for corner in polygon for x in corner]
    if any(len(corner) != 3 for polygon in polygons for corner in polygon):
        raise ZshiftError(Status.DOMAIN, "every receiver corner needs 3 coordinates (x, y, z)")
    corners = (_ctypes.c_float * max(len(flat), 1))(*flat)
    counts = (_ctypes.c_uint32 * max(len(polygons), 1))(*[len(p) for p in polygons])
    lib = _lib()
    fn = lib.zshift_shadow_bias_receivers
    fn.argtypes = [_ctypes.POINTER(_ShadowMap), _ctypes.POINTER(_ctypes.c_float),
                   _ctypes.POINTER(_ctypes.c_uint32), _ctypes.c_uint32, _ctypes.POINTER(_ShadowBias)]
    fn.restype = _ctypes.c_int32
    out = _ShadowBias()
    _check(fn(_ctypes.byref(record), corners, counts, len(polygons), _ctypes.byref(out)))
    return ShadowBias(*(getattr(out, name) for name, _ in _ShadowBias._fields_))
