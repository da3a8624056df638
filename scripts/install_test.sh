#!/usr/bin/env bash
# Part of `make test` (after scripts/run_tests.sh's devel-space tests): installs the workspace into
# install/ (catkin_make install on the same build/) and runs one rostest with nothing but
# install/setup.bash sourced: the bag regression with BioBin, saliency and recognition as nodelets in
# one manager (biovision_bringup tabletop_bag_nodelets.test). It fails when a launch file, config,
# model, plugin description or library was not installed, or is found in the source tree instead.
# Results go to build/test_results/install_space/, so scripts/test_summary.py counts them; the test
# is named tabletop_bag_nodelets_installed there.
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:/bin:$PATH
root=$PWD
CATKIN_ARGS=${CATKIN_ARGS:--DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=ON}
results=$root/build/test_results/install_space
log=$root/build/install_test.log
ros_home=${ROS_HOME:-$root/build/ros_home}
rm -rf "$results" install
mkdir -p "$results" "$ros_home"
# A JUnit case of this script's own, so that an install that fails counts in the summary.
junit() {  # name, failure message (empty = passed)
  local body=""
  [[ -n "$2" ]] && body="<failure message=\"$2\">see build/install_test.log</failure>"
  printf '<?xml version="1.0"?>\n<testsuite name="install_space" tests="1">\n<testcase classname="install_space" name="%s">%s</testcase>\n</testsuite>\n' \
    "$1" "$body" >"$results/$1.xml"
}

echo "install_test: catkin_make install into install/ (log: build/install_test.log)"
# shellcheck disable=SC2086
if ! catkin_make -j"${JOBS:-2}" $CATKIN_ARGS install >"$log" 2>&1; then
  tail -n 20 "$log"
  echo "install_test: catkin_make install FAILED"
  junit catkin_make_install "catkin_make install failed"
  exit 1
fi
junit catkin_make_install ""

# A clean environment: only the install space over Debian's ROS in /usr.
echo "install_test: rostest biovision_bringup tabletop_bag_nodelets.test from install/"
env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 ROS_HOME="$ros_home" \
  BIOVISION_SHARED="${BIOVISION_SHARED:-$(cd .. && pwd)/shared}" \
  bash -c '
    source install/setup.bash   # Debian'"'"'s profile.d scripts need set +u
    set -u
    for pkg in biovision_bringup biovision_stereo biovision_saliency biovision_recognition; do
      where=$(rospack find $pkg)
      if [[ $where != "$PWD/install/share/$pkg" ]]; then
        echo "install_test: $pkg found at $where, not in install/share"; exit 1
      fi
    done
    rostest --results-base-dir "$1" biovision_bringup tabletop_bag_nodelets.test \
      bag:="$PWD/rosbags/tabletop_sweep.bag" test_name:=tabletop_bag_nodelets_installed
  ' install_test "$results" >>"$log" 2>&1
rc=$?
grep -E "^\[biovision_bringup|RESULT|install_test:" "$log" | tail -n 5
if ! ls "$results"/biovision_bringup/*.xml >/dev/null 2>&1; then
  echo "install_test: the rostest wrote no result (see build/install_test.log)"
  junit rostest_from_install "no result: the rostest did not run from install/"
  exit 1
fi
exit $rc
