#!/usr/bin/env bash
# `make bench` entry "loop" (issue 21): biovision_bringup's loop_bench.launch on a private master port, so it
# never joins a roscore the user runs. usage: scripts/loop_bench.sh JSON [roslaunch args...]
set -uo pipefail
json=$(realpath -m "$1")
shift
export ROS_HOME=${ROS_HOME:-$PWD/build/ros_home}
mkdir -p "$ROS_HOME"
port=$((20000 + RANDOM % 20000))
export ROS_MASTER_URI=http://localhost:$port
rm -f "$json"
timeout 900 roslaunch -p "$port" biovision_bringup loop_bench.launch json:="$json" "$@"
[[ -f "$json" ]]
