#!/usr/bin/env bash
# Installs the Debian packages the BioVision workspace needs. Idempotent: when every package is
# already installed it only runs dpkg-query and exits, so `make` targets can call it every time.
# Works as root or through sudo.
set -euo pipefail

PACKAGES=(
  # build tools and the ROS 1 core from Debian (no /opt/ros)
  build-essential cmake catkin catkin-lint python3-catkin-pkg python3-empy clang-format
  ros-base-dev ros-core-dev rosbash rosout python3-roslaunch python3-rostopic python3-rosnode
  python3-rosparam python3-rosmsg python3-rosservice python3-rosbag python3-rostest librostest-dev
  python3-rosunit
  # messages
  ros-message-generation ros-message-runtime ros-std-msgs ros-std-srvs ros-geometry-msgs
  ros-sensor-msgs ros-stereo-msgs ros-nav-msgs ros-visualization-msgs ros-diagnostic-msgs
  ros-actionlib-msgs ros-rosgraph-msgs libactionlib-dev python3-actionlib
  python3-rospy python3-std-msgs python3-sensor-msgs python3-geometry-msgs python3-stereo-msgs
  python3-nav-msgs python3-visualization-msgs python3-diagnostic-msgs python3-actionlib-msgs
  python3-tf2-msgs
  # ROS C++ libraries
  libtf2-dev libtf2-ros-dev libtf2-eigen-dev libtf2-geometry-msgs-dev python3-tf2-ros tf2-tools
  libimage-transport-dev image-transport-tools libcv-bridge-dev libimage-geometry-dev
  libnodelet-dev libnodeletlib-dev pluginlib-dev
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libmessage-filters-dev libcamera-info-manager-dev libdiagnostic-updater-dev python3-diagnostic-updater
  librosbag-dev liburdf-dev ros-robot-state-publisher
  # image pipeline peers and viewers
  ros-stereo-image-proc ros-image-proc rviz xvfb xauth
  # biovision_monitor's rviz panel plugin (DisplayStatus: each display's status on a topic); Qt 5 comes with it
  librviz-dev
  # real images for the demo that need no ../shared (/usr/share/doc/opencv-doc/examples/data); also the
  # descriptor's held-out evaluation material (graf1/graf3 + H1to3p, never trained on)
  opencv-doc
  # libraries the ROS-free cores use
  libopencv-dev libopencv-contrib-dev libeigen3-dev liblinear-dev libyaml-cpp-dev
  # biovision_v1: the Gabor bank's DFTs (FFTW3, 2-4x cv::dft's speed at the bank's sizes)
  libfftw3-dev
  # biovision_common: tool options, JSON, CRC
  libcli11-dev nlohmann-json3-dev zlib1g-dev
  # biovision_memory: the memory database (and the sqlite3 shell to inspect it)
  libsqlite3-dev sqlite3
  # bumblebee2_driver: IEEE-1394 capture (pkg-config finds it)
  libdc1394-dev pkg-config
  # tests and benchmarks
  googletest libgtest-dev libbenchmark-dev valgrind
  # the rviz rostest: screenshots of its private Xvfb display (Xlib)
  libx11-dev
)
# `make bench` only (scripts/bench.sh sets BIOVISION_BENCH=1): image collections of biovision_recognition's
# descriptor training corpus and held-out split (train_descriptor/descriptor_eval --images; data only,
# 250 MB, so build, test and demo do not download them); OpenCV's pretrained Haar/LBP face cascades,
# the peers of biovision_hri's face detector (detector_eval --baseline-cascades, data only).
if [[ ${BIOVISION_BENCH:-0} == 1 ]]; then
  PACKAGES+=(visp-images-data python3-skimage opencv-data)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
echo "setup: installing ${#missing[@]} package(s): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "setup: done"
