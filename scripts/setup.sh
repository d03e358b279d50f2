#!/usr/bin/env bash
# Installs every Debian package the project needs (idempotent: a quick dpkg check when all is present),
# then builds the package in the git-ignored catkin workspace .ws/. Works from any directory, as root
# (or with sudo available). Usage: scripts/setup.sh [--no-build]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

PACKAGES=(
  # toolchain: a minimal Debian 12 has none of it
  build-essential cmake git pkg-config
  # pgrep (scripts/run_tests.sh stops its background job with its children on a failure)
  procps
  # ROS 1 as Debian ships it (no /opt/ros)
  catkin ros-message-generation ros-base-dev python3-rostest python3-roslaunch python3-rosbag
  python3-rosunit librostest-dev
  # static_transform_publisher (demo.launch places the parts side by side)
  tf2-tools
  librosbag-dev libcv-bridge-dev libimage-transport-dev libtf2-ros-dev libtf2-geometry-msgs-dev
  # lockstep_player (a bag played in step with the node it feeds: the demo, the rostests)
  libtopic-tools-dev
  # every node as a nodelet (src/nodelets), and the nodelet manager
  libnodeletlib-dev pluginlib-dev libnodeletlib-tools
  # image_transport's republish (test/ros/compressed_camera.test); image_geometry (rectification)
  image-transport-tools libimage-geometry-dev
  libtf2-eigen-dev libsensor-msgs-dev libgeometry-msgs-dev libnav-msgs-dev libvisualization-msgs-dev
  libdiagnostic-updater-dev libdiagnostic-msgs-dev libdynamic-reconfigure-config-init-mutex-dev
  python3-dynamic-reconfigure rosbash libstd-srvs-dev python3-std-srvs
  # Python message modules so that rostopic/rosbag can print the project's topics
  python3-sensor-msgs python3-geometry-msgs python3-nav-msgs python3-tf2-msgs python3-visualization-msgs
  python3-diagnostic-msgs python3-std-msgs
  # core libraries
  libeigen3-dev libopencv-dev libyaml-cpp-dev libbz2-dev libsqlite3-dev
  # the pose graph of the SLAM loop closing (slam/pose_graph.h)
  libceres-dev
  # the tools' command lines (src/tools/command_line.h)
  libcli11-dev
  # OpenCV's CSRT and KCF trackers, the peers of evaluate_tracking
  libopencv-contrib-dev
  # sample videos (a face sequence) for the tracking evaluation
  opencv-doc
  # tests and benchmarks
  libgtest-dev googletest libbenchmark-dev
  # clang with its sanitizer and libFuzzer runtimes (scripts/fuzz.sh; gcc's sanitizers come with build-essential)
  clang libclang-rt-14-dev
  # lld links the sanitizer tree's test programs (scripts/check_core.sh) in a fraction of ld's time
  lld
  # plots, rviz under a virtual display
  python3-matplotlib python3-yaml python3-numpy rviz xvfb xauth
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

[ "${1:-}" = "--no-build" ] && exit 0

mkdir -p "$AP_WS/src"
ln -sfn "$AP_ROOT" "$AP_WS/src/adaptive_perception"
cd "$AP_WS"
JOBS="${AP_JOBS:-$(nproc)}"
echo "setup: building in $AP_WS (-j$JOBS)"
catkin_make -DCMAKE_BUILD_TYPE=Release -j"$JOBS" > "$AP_WS/build.log" 2>&1 || {
  tail -n 60 "$AP_WS/build.log"; echo "setup: build FAILED (full log: $AP_WS/build.log)"; exit 1; }
echo "setup: build ok"
