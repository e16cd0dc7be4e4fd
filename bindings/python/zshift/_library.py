"""Finding and loading the zshift shared library, and declaring its C signatures.

Search order: the ``ZSHIFT_LIBRARY`` environment variable (a path to the library file; if it is
set, nothing else is tried, so a wrong path fails loudly instead of silently picking up another
copy), then the library ``pip install .`` put inside this package (``zshift/_zshift*.so``, built
by setuptools-rust from the crate, see pyproject.toml), then ``target/release`` and
``target/debug`` of the source tree this package sits in (a development checkout), then the
system's library path (an installed copy, via ``ctypes.util.find_library``).
"""

import ctypes
import ctypes.util
import os
import sys
import sysconfig
from pathlib import Path

# The file name cargo gives the cdylib on each platform.
if sys.platform == "win32":
    _FILE_NAME = "zshift.dll"
elif sys.platform == "darwin":
    _FILE_NAME = "libzshift.dylib"
else:
    _FILE_NAME = "libzshift.so"

# bindings/python/zshift/_library.py -> the repository root is three levels up.
_SOURCE_ROOT = Path(__file__).resolve().parents[3]
_PACKAGE_DIR = Path(__file__).resolve().parent


def packaged():
    """The library ``pip install`` placed in this package, or ``None`` in a source checkout.

    setuptools-rust names it like an extension module: ``_zshift`` + this interpreter's
    extension suffix (``.cpython-311-x86_64-linux-gnu.so``), or ``.abi3.so`` for a limited-API
    wheel; it is a plain C library all the same, loaded with ctypes.
    """
    suffixes = [sysconfig.get_config_var("EXT_SUFFIX") or "", ".abi3" + (".pyd" if sys.platform == "win32" else ".so")]
    for suffix in suffixes:
        path = _PACKAGE_DIR / ("_zshift" + suffix)
        if suffix and path.is_file():
            return path
    return None


class LibraryNotFound(ImportError):
    """No zshift shared library could be loaded; the message lists every place tried."""


def candidates():
    """The paths tried, in order (``None`` stands for the system's library search)."""
    override = os.environ.get("ZSHIFT_LIBRARY")
    if override:
        return [Path(override)]
    inside = packaged()
    return ([inside] if inside is not None else []) + [
        _SOURCE_ROOT / "target" / "release" / _FILE_NAME,
        _SOURCE_ROOT / "target" / "debug" / _FILE_NAME,
        None,
    ]


def load():
    """Loads the library and declares its signatures; returns ``(CDLL, path)``.

    Raises :class:`LibraryNotFound` naming every path tried.
    """
    tried = []
    for path in candidates():
        if path is None:
            found = ctypes.util.find_library("zshift")
            if found is None:
                tried.append("the system library path (find_library('zshift'))")
                continue
            path = found
        elif not Path(path).is_file():
            tried.append(f"{path} (no such file)")
            continue
        try:
            lib = ctypes.CDLL(str(path))
        except OSError as error:
            tried.append(f"{path} ({error})")
            continue
        _declare(lib)
        return lib, str(path)
    raise LibraryNotFound(
        "cannot load the zshift library; install the package with `pip install .` from the "
        "repository root, or build it with `cargo build --release`, or set ZSHIFT_LIBRARY to its "
        "path. Tried: " + "; ".join(tried)
    )


class ZshiftPipeline(ctypes.Structure):
    """The C ``ZshiftPipeline``, field for field: glViewport's x, y; glDepthRange (0, 0: the
    default 0, 1); world_reach (0: eye-space vertices); eye_first; the view matrix (NULL: not
    given) and the world box it maps (min xyz, max xyz)."""

    _fields_ = [
        ("viewport_x", ctypes.c_uint32), ("viewport_y", ctypes.c_uint32),
        ("depth_range_near", ctypes.c_double), ("depth_range_far", ctypes.c_double),
        ("world_reach", ctypes.c_double), ("eye_first", ctypes.c_uint32),
        ("view_matrix", ctypes.c_void_p), ("world_box", ctypes.c_double * 6),
    ]


class ZshiftScene(ctypes.Structure):
    """The C ``ZshiftScene`` (include/zshift.h), field for field."""

    _fields_ = [
        ("l", ctypes.c_double), ("r", ctypes.c_double), ("b", ctypes.c_double), ("t", ctypes.c_double),
        ("n", ctypes.c_double), ("f", ctypes.c_double),
        ("viewport_width", ctypes.c_uint32), ("viewport_height", ctypes.c_uint32),
        ("depth_format", ctypes.c_uint32),
        ("decal_near", ctypes.c_double), ("decal_far", ctypes.c_double), ("slope", ctypes.c_double),
        ("exact_depth", ctypes.c_uint32), ("subpixel_bits", ctypes.c_int32),
        ("depth_func", ctypes.c_uint32), ("base_reach", ctypes.c_double),
        # const ZshiftProfile *: NULL for the worst case (zshift.profile_worst_case()).
        ("profile", ctypes.c_void_p),
        # const float *: the decal's eye-space corners (3 floats each), or NULL.
        ("decal_corners", ctypes.c_void_p), ("decal_corner_count", ctypes.c_uint32),
        # The engine's pipeline (zeroed: the defaults).
        ("pipeline", ZshiftPipeline),
    ]


class ZshiftRecommendation(ctypes.Structure):
    """The C ``ZshiftRecommendation``, field for field."""

    _fields_ = [(name, ctypes.c_double) for name in (
        "epsilon", "ndc_offset", "window_offset", "delta_at_far", "bleed_gap",
        "polygon_offset_factor", "polygon_offset_units",
        "quantum", "transform", "vertex", "interpolation", "snap", "plane", "clip",
    )]


def _declare(lib):
    """Declares argument and result types, so ctypes converts and checks every call."""
    d, u32, i32, status = ctypes.c_double, ctypes.c_uint32, ctypes.c_int32, ctypes.c_int32
    float_out, double_out = ctypes.POINTER(ctypes.c_float), ctypes.POINTER(ctypes.c_double)
    signatures = {
        "zshift_frustum": [d] * 6 + [float_out],
        "zshift_load_offset_matrix": [d] * 8 + [float_out],
        "zshift_epsilon": [d] * 4 + [double_out],
        "zshift_min_epsilon": [d, d, u32, double_out],
        "zshift_min_delta_toward": [d, d, u32, d, double_out],
        "zshift_max_delta_away": [d, d, u32, d, double_out],
        "zshift_window_depth": [d, d, d, double_out],
        "zshift_depth_resolution": [d, d, u32, d, double_out],
        "zshift_perspective": [d] * 4 + [float_out],
        "zshift_projection": [d] * 6 + [i32, float_out],
        "zshift_offset_projection": [d] * 6 + [i32, d, d, float_out],
        "zshift_offset_perspective": [d] * 4 + [i32, d, d, float_out],
        "zshift_tweaked_infinite": [d] * 6 + [float_out],
        "zshift_offset_tweaked_infinite": [d] * 8 + [float_out],
        "zshift_median_ndc_offset": [d] * 3 + [double_out],
        "zshift_window_depth_clip": [d, d, i32, d, double_out],
        "zshift_depth_step": [d, d, i32, i32, d, double_out],
        "zshift_median_depth_step": [d, i32, d, double_out],
        "zshift_min_ndc_offset": [d, d, i32, i32, d, double_out],
        "zshift_min_epsilon_clip": [d, d, i32, i32, d, double_out],
        "zshift_min_relative_epsilon": [d, d, i32, i32, d, double_out],
        "zshift_bias_of_shift": [d, d, i32, i32, i32, d, d, double_out],
        "zshift_shift_of_bias": [d, d, i32, i32, i32, d, d, double_out],
        "zshift_tight_planes": [d, d, double_out],
        "zshift_range_offset": [d, d, i32, i32, i32, d, d, d, double_out],
    }
    for name, argtypes in signatures.items():
        fn = getattr(lib, name)
        fn.argtypes = argtypes
        fn.restype = status
    scene = ctypes.POINTER(ZshiftScene)
    lib.zshift_recommend.argtypes = [scene, ctypes.POINTER(ZshiftRecommendation)]
    lib.zshift_recommend.restype = status
    lib.zshift_recommend_matrix.argtypes = [scene, float_out]
    lib.zshift_recommend_matrix.restype = status
    lib.zshift_recommend_clip.argtypes = [scene, ctypes.c_int32, ctypes.POINTER(ZshiftRecommendation)]
    lib.zshift_recommend_clip.restype = status
    lib.zshift_recommend_clip_matrix.argtypes = [scene, ctypes.c_int32, float_out]
    lib.zshift_recommend_clip_matrix.restype = status
    lib.zshift_status_message.argtypes = [status]
    lib.zshift_status_message.restype = ctypes.c_char_p
    lib.zshift_version.argtypes = []
    lib.zshift_version.restype = ctypes.c_char_p
