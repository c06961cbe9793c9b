#!/usr/bin/env bash
# `cmake --install` into a fresh prefix, without root; then from that prefix alone: the binary runs, a
# consumer project builds against find_package(rupture) and computes the uniform bundle, and the
# Python package imports (when built).  install_test.sh BUILD_DIR SOURCE_DIR PYTHON|"" WORK_DIR
set -euo pipefail
build=$1 source=$2 python=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >"$work/install.log"
"$prefix/bin/rupture" fbm theory --dist uniform --json | grep -q '"x_c": 0.5'
cmake -S "$source/tests/install/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >"$work/configure.log"
cmake --build "$work/consumer" >"$work/build.log"
out=$("$work/consumer/consumer")
echo "$out"
grep -q "x_p 0.333333 x_c 0.500000 x_m 0.666667 A_r band 0.837-1.333" <<<"$out"
if [[ -n "$python" ]]; then
  site=$(find "$prefix" -type d -name site-packages | head -1)
  (cd "$work" && PYTHONPATH=$site "$python" -c 'import rupture; assert rupture.fbm.theory("uniform")["x_c"] == 0.5; print("python", rupture.__file__)')
fi
