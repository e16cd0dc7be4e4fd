#!/usr/bin/env bash
# Installs zshift into a scratch PREFIX with scripts/install, then builds and runs C and C++
# programs against the installed copy only: through pkg-config (shared and --static) and through
# CMake's find_package (shared and static targets). Fails with the reason if a tool is missing.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
work=$root/target/packaging-test
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix

for tool in pkg-config cmake cc c++; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is not installed (scripts/setup installs it)" >&2; exit 1; }
done

scripts/install "$prefix"
want="zshift $(sed -n 's/^version *= *"\(.*\)"/\1/p' Cargo.toml | head -n 1), C ABI"

# The programs must use the installed library, never the build tree's.
uses_prefix() {
  local linked
  linked=$(LD_LIBRARY_PATH="$prefix/lib" ldd "$1" | grep libzshift || true)
  case "$linked" in
    "") echo "static" ;;
    *"$prefix/lib/libzshift.so"*) echo "installed" ;;
    *) echo "FAIL: $1 links $linked, not the installed copy" >&2; exit 1 ;;
  esac
}

echo "-- pkg-config: shared"
# [quickstart-pkg-config]
cc tests/packaging/consumer.c $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs zshift) -o "$work/consumer_pc"
# [/quickstart-pkg-config]
[ "$(uses_prefix "$work/consumer_pc")" = installed ]
LD_LIBRARY_PATH="$prefix/lib" "$work/consumer_pc" | grep -F "$want"

echo "-- pkg-config: static"
cc tests/packaging/consumer.c -o "$work/consumer_pc_static" \
  $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags zshift) \
  "$prefix/lib/libzshift.a" $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --libs-only-l --static zshift | sed 's/-lzshift//')
[ "$(uses_prefix "$work/consumer_pc_static")" = static ]
"$work/consumer_pc_static" | grep -F "$want"

echo "-- CMake: find_package(zshift 0.1)"
cmake -S tests/packaging -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >"$work/cmake.log" 2>&1 \
  || { cat "$work/cmake.log" >&2; echo "FAIL: CMake could not configure against the installed package" >&2; exit 1; }
cmake --build "$work/cmake" >>"$work/cmake.log" 2>&1 \
  || { cat "$work/cmake.log" >&2; echo "FAIL: CMake could not build against the installed package" >&2; exit 1; }
[ "$(uses_prefix "$work/cmake/consumer_c")" = installed ]
[ "$(uses_prefix "$work/cmake/consumer_cpp")" = static ]
LD_LIBRARY_PATH="$prefix/lib" "$work/cmake/consumer_c" | grep -F "$want"
"$work/cmake/consumer_cpp" | grep -F "zshift"

echo "-- CMake: an incompatible version request is refused"
sed 's/find_package(zshift 0.1 REQUIRED)/find_package(zshift 0.2 REQUIRED)/' tests/packaging/CMakeLists.txt > "$work/newer.txt"
mkdir -p "$work/newer"
cp "$work/newer.txt" "$work/newer/CMakeLists.txt"
cp tests/packaging/consumer.c tests/packaging/consumer.cpp "$work/newer/"
if cmake -S "$work/newer" -B "$work/newer/build" -DCMAKE_PREFIX_PATH="$prefix" >"$work/newer.log" 2>&1; then
  echo "FAIL: find_package(zshift 0.2) accepted version $(sed -n 's/^version *= *"\(.*\)"/\1/p' Cargo.toml | head -n 1)" >&2
  exit 1
fi
grep -q "considered but not accepted" "$work/newer.log" || { cat "$work/newer.log" >&2; exit 1; }

echo "packaging: pkg-config and CMake consumers build and run against $prefix"
