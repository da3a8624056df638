#!/usr/bin/env bash
# Re-records the committed bags from the simulator (run from anywhere after `make build`):
#   tabletop_sweep.bag  the table-top world, head sweeping +-69 deg, 6 s of sim time
#   corridor_drive.bag  the corridor world, driving forward at 0.3 m/s, 6 s of sim time
# `record.sh tabletop_sweep` re-records only that one.
# Raw stereo pair + camera_info at 5 Hz (320x240), joint_states, odom, tf, ground-truth pose and
# ground-truth disparity of the left view (the bag regression tests score BioBin against it); bz2.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
export PATH=/usr/bin:/bin:$PATH
set +u; source "$root/devel/setup.bash"; set -u
export ROS_HOME=${ROS_HOME:-$root/build/ros_home}
topics="/stereo/left/image_raw /stereo/right/image_raw /stereo/left/camera_info /stereo/right/camera_info
        /joint_states /odom /tf /tf_static /sim/ground_truth/pose /sim/objects /stereo/ground_truth/disparity"

record() {  # name world mode extra-args
  local name=$1 world=$2 mode=$3
  local port=$((21000 + RANDOM % 10000))
  export ROS_MASTER_URI=http://localhost:$port
  roslaunch -p "$port" biovision_bringup sim.launch world:="$(rospack find biovision_bringup)/config/worlds/$world" camera_rate:=5 rate:=1.0 \
    >"$ROS_HOME/record_$name.log" 2>&1 &
  local launch=$!
  sleep 4
  rosrun biovision_sim scripted_motion _mode:="$mode" >/dev/null 2>&1 &
  local motion=$!
  # rosbag record stops itself after 6 s of (sim) time.
  rosbag record --bz2 --duration=6 -O "$here/$name.bag" $topics >/dev/null
  kill $motion $launch 2>/dev/null || true
  wait $launch 2>/dev/null || true
  echo "recorded $here/$name.bag ($(du -h "$here/$name.bag" | cut -f1))"
}

which=${1:-all}
[[ $which == all || $which == tabletop_sweep ]] && record tabletop_sweep tabletop.yaml sweep
[[ $which == all || $which == corridor_drive ]] && record corridor_drive corridor.yaml drive
exit 0
