#!/usr/bin/env bash
# The package as another package sees it: installs it into a temporary directory (catkin_make
# install with DESTDIR, removed at the end: an install space left inside the package tree would make
# `rosrun adaptive_perception <node>` ambiguous) and checks that
#   1. a downstream catkin package (test/install/ap_downstream) builds against the install space
#      alone, using a message, a service and the core library, and runs;
#   2. the installed scripts keep their execute bit;
#   3. the installed libraries and executables hold no path of the source tree;
#   4. an installed tool, run from another directory with only the install space sourced, finds the
#      package's config files there;
#   5. the installed package exports its nodelets and its image transport, with their libraries.
# Needs a built workspace (scripts/setup.sh). Ends with `check_install: passed` (exit 0) or
# `check_install: FAILED: <what>` (exit 1). About a minute after a build.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
fail() { echo "check_install: FAILED: $*"; exit 1; }
cd "$AP_WS" || fail "no workspace at $AP_WS (run scripts/setup.sh)"
set +u; source devel/setup.bash; set -u
JOBS="${AP_JOBS:-$(nproc)}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
prefix="$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' build/CMakeCache.txt)"
[ -n "$prefix" ] || fail "no CMAKE_INSTALL_PREFIX in $AP_WS/build/CMakeCache.txt"
DESTDIR="$tmp/dest" catkin_make -j"$JOBS" install > "$AP_WS/install.log" 2>&1 \
  || { tail -n 30 "$AP_WS/install.log"; fail "catkin_make install (log: $AP_WS/install.log)"; }
INSTALL="$tmp/dest$prefix"
[ -f "$INSTALL/setup.bash" ] || fail "catkin_make install wrote no $INSTALL/setup.bash"
SHARE="$INSTALL/share/adaptive_perception"

# 2. Execute bits.
for s in "$SHARE"/scripts/*.sh; do
  [ -x "$s" ] || fail "$s was installed without its execute bit"
done

# 3. No source path in what was installed (the tree, and the path the workspace links it under).
for dir in "$AP_ROOT" "$(readlink -f "$AP_WS/src/adaptive_perception")" "$AP_WS/src/adaptive_perception"; do
  hits="$(grep -l -F "$dir" "$INSTALL"/lib/*.so "$INSTALL"/lib/adaptive_perception/* 2> /dev/null | head -n 3)"
  [ -z "$hits" ] || fail "the source path $dir is compiled into: $hits"
done

# 1. A downstream package against the install space only.
mkdir -p "$tmp/ws/src"
cp -r "$AP_ROOT/test/install/ap_downstream" "$tmp/ws/src/"
(
  env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c "
    source '$INSTALL/setup.bash' && cd '$tmp/ws' &&
    catkin_make -j$JOBS > build.log 2>&1 || { tail -n 30 build.log; exit 1; }
    ./devel/lib/ap_downstream/ap_downstream"
) || fail "the downstream package (test/install/ap_downstream) did not build or run against $INSTALL"

# 4. An installed tool finds config/ in the install space.
out="$(cd "$tmp" && env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c "source '$INSTALL/setup.bash' &&
  '$INSTALL/lib/adaptive_perception/bench_rbpf' --particles 20 --frames 2 --threads 1" 2>&1 | tail -n 1)"
case "$out" in
  bench_rbpf:*) echo "$out" ;;
  *) fail "the installed bench_rbpf did not run from the install space: $out" ;;
esac
# 5. The installed plugins: every node as a nodelet, and the compressed image transport.
out="$(env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c "source '$INSTALL/setup.bash' &&
  rospack plugins --attrib=plugin nodelet; rospack plugins --attrib=plugin image_transport" 2>&1)"
for xml in nodelet_plugins.xml image_transport_plugins.xml; do
  echo "$out" | grep -q "^adaptive_perception $SHARE/$xml\$" ||
    fail "the installed package does not export $SHARE/$xml (rospack plugins said: $out)"
done
for lib in adaptive_perception_nodelets adaptive_perception_image_transport; do
  [ -f "$INSTALL/lib/lib$lib.so" ] || fail "lib$lib.so was not installed in $INSTALL/lib"
done
echo "check_install: passed"
