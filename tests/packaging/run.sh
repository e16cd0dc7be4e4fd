#!/usr/bin/env bash
# Installs zshift into a scratch PREFIX with scripts/install, checks the layout (SONAME, symlinks),
# then builds and runs C and C++ programs against the installed copy only: the README's
# "use it from your own program" lines, pkg-config (shared, zshift-static, and --static for a
# fully static program) and CMake's find_package (shared and static targets). Programs run with
# no LD_LIBRARY_PATH: they must find the library through what the .pc file and CMake give them.
# Fails with the reason if a tool is missing.
set -euo pipefail
cd "$(dirname "$0")/../.."
unset LD_LIBRARY_PATH
root=$PWD
work=$root/target/packaging-test
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix

for tool in pkg-config cmake cc c++ readelf; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is not installed (scripts/setup installs it)" >&2; exit 1; }
done
fail() { echo "FAIL: $*" >&2; exit 1; }

P=$prefix
# [quickstart-install]
scripts/install $P   # P: an absolute prefix, e.g. P=$HOME/.local (run in this repository)
# [/quickstart-install]
version=$(sed -n 's/^version *= *"\(.*\)"/\1/p' Cargo.toml | head -n 1)
soname=libzshift.so.${version%%.*}
want="zshift $version, C ABI"

echo "-- layout: $soname"
readelf -d "$prefix/lib/libzshift.so.$version" | grep -F "Library soname: [$soname]" \
  || fail "the installed libzshift.so.$version has no SONAME $soname"
[ "$(readlink "$prefix/lib/libzshift.so")" = "$soname" ] || fail "libzshift.so does not point to $soname"
[ "$(readlink "$prefix/lib/$soname")" = "libzshift.so.$version" ] || fail "$soname does not point to libzshift.so.$version"
for f in include/zshift.h include/zshift.hpp lib/libzshift.a lib/pkgconfig/zshift.pc lib/pkgconfig/zshift-static.pc \
  lib/cmake/zshift/zshiftConfig.cmake lib/cmake/zshift/zshiftConfigVersion.cmake; do
  [ -f "$prefix/$f" ] || fail "$prefix/$f was not installed"
done

# How a program links and loads zshift: "dynamic" (records the SONAME and the loader opens the
# installed copy, with no LD_LIBRARY_PATH), "static" (libzshift.a inside, other libraries
# dynamic) or "fully static" (no dynamic section at all).
linkage() {
  local needed
  needed=$(readelf -d "$1" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
  if [ -z "$(readelf -d "$1" | grep -F '(NEEDED)' || true)" ]; then
    echo "fully static"
  elif echo "$needed" | grep -qx "$soname"; then
    local loads
    loads=$(ldd "$1" | grep libzshift)
    case "$loads" in
      *"$soname => $prefix/lib/$soname "*) ;;
      *) fail "$1 loads $loads, not $prefix/lib/$soname" ;;
    esac
    echo "dynamic"
  elif echo "$needed" | grep -q libzshift; then
    fail "$1 records $(echo "$needed" | grep libzshift), not the SONAME $soname"
  else
    echo "static"
  fi
}
expect() { # PROGRAM LINKAGE OUTPUT
  local got
  got=$(linkage "$1")
  [ "$got" = "$2" ] || fail "$1 is linked $got, expected $2"
  "$1" | grep -F "$3" || fail "$1 did not print '$3'"
}

echo "-- the README's lines: examples/consumer built with C, C++, pkg-config, CMake (P is the prefix)"
# They run in a copy of examples/consumer, so the tree stays clean.
mkdir -p "$work/quick/examples"
cp -r examples/consumer "$work/quick/examples/"
rm -rf "$work/quick/examples/consumer/build" "$work/quick/examples/consumer"/app_*
(
  cd "$work/quick"
  set -x
  # [quickstart-use-c]
  cd examples/consumer                                                                        # main.c, main.cpp, CMakeLists.txt
  cc main.c -I$P/include -L$P/lib -Wl,-rpath,$P/lib -lzshift -o app_c                         # C
  c++ -std=c++17 main.cpp -I$P/include -L$P/lib -Wl,-rpath,$P/lib -lzshift -o app_cpp         # C++ (zshift.hpp)
  cc main.c $(PKG_CONFIG_PATH=$P/lib/pkgconfig pkg-config --cflags --libs zshift) -o app_pc   # pkg-config
  cmake -S . -B build -DCMAKE_PREFIX_PATH=$P && cmake --build build                           # CMake: app, app_cpp
  ./app_c && ./build/app_cpp                                                                  # run with no LD_LIBRARY_PATH
  # [/quickstart-use-c]
) >"$work/quick.log" 2>&1 || { cat "$work/quick.log" >&2; fail "a README line did not build"; }
cat "$work/quick.log" | grep -v '^+' || true
quick=$work/quick/examples/consumer
expect "$quick/app_c" dynamic "$want"
expect "$quick/app_cpp" dynamic "zshift $version (C++)"
expect "$quick/app_pc" dynamic "$want"
expect "$quick/build/app" dynamic "$want"
expect "$quick/build/app_cpp" static "zshift $version (C++)"

echo "-- pkg-config: shared"
# [quickstart-pkg-config]
cc tests/packaging/consumer.c $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs zshift) -o "$work/consumer_pc"
# [/quickstart-pkg-config]
expect "$work/consumer_pc" dynamic "$want"

echo "-- pkg-config: zshift-static (libzshift.a, the rest dynamic)"
# [quickstart-pkg-config-static]
cc tests/packaging/consumer.c $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs zshift-static) -o "$work/consumer_pc_static"
# [/quickstart-pkg-config-static]
expect "$work/consumer_pc_static" static "$want"

echo "-- pkg-config --static: a fully static program"
# glibc warns that getaddrinfo and getpwuid_r (in Rust's std, unused here) need its shared
# libraries at run time if called; the warnings are kept in the log.
{
  # [quickstart-pkg-config-fully-static]
  cc -static tests/packaging/consumer.c $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --static --cflags --libs zshift) -o "$work/consumer_fully_static"
  # [/quickstart-pkg-config-fully-static]
} 2>"$work/static.log"
expect "$work/consumer_fully_static" "fully static" "$want"

echo "-- pkg-config: C++ through zshift.hpp"
c++ -std=c++17 tests/packaging/consumer.cpp $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs zshift) -o "$work/consumer_pc_cpp"
expect "$work/consumer_pc_cpp" dynamic "zshift $version (C++)"

echo "-- CMake: find_package(zshift 0.1)"
cmake -S tests/packaging -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >"$work/cmake.log" 2>&1 \
  || { cat "$work/cmake.log" >&2; fail "CMake could not configure against the installed package"; }
cmake --build "$work/cmake" >>"$work/cmake.log" 2>&1 \
  || { cat "$work/cmake.log" >&2; fail "CMake could not build against the installed package"; }
expect "$work/cmake/consumer_c" dynamic "$want"
expect "$work/cmake/consumer_cpp" static "zshift $version (C++)"

echo "-- CMake: an incompatible version request is refused"
mkdir -p "$work/newer"
sed 's/find_package(zshift 0.1 REQUIRED)/find_package(zshift 0.2 REQUIRED)/' tests/packaging/CMakeLists.txt > "$work/newer/CMakeLists.txt"
cp tests/packaging/consumer.c tests/packaging/consumer.cpp "$work/newer/"
if cmake -S "$work/newer" -B "$work/newer/build" -DCMAKE_PREFIX_PATH="$prefix" >"$work/newer.log" 2>&1; then
  fail "find_package(zshift 0.2) accepted version $version"
fi
grep -q "considered but not accepted" "$work/newer.log" || { cat "$work/newer.log" >&2; exit 1; }

echo "-- DESTDIR staging: files under DESTDIR, the .pc names the final prefix"
DESTDIR="$work/stage" scripts/install /usr >"$work/stage.log" 2>&1 || { cat "$work/stage.log" >&2; fail "DESTDIR install failed"; }
[ -L "$work/stage/usr/lib/$soname" ] || fail "DESTDIR install left no $soname"
grep -qx "prefix=/usr" "$work/stage/usr/lib/pkgconfig/zshift.pc" || fail "the staged zshift.pc does not say prefix=/usr"
grep '^Libs:' "$work/stage/usr/lib/pkgconfig/zshift.pc" | grep -q rpath && fail "the staged zshift.pc adds an rpath under /usr"

echo "packaging: the README lines, pkg-config (shared, static, fully static) and CMake consumers build and run against $prefix"
