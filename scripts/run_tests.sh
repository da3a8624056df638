#!/usr/bin/env bash
# Runs every gtest and rostest of the workspace (each rostest brings up its own real roscore), then
# one rostest from the install space (scripts/install_test.sh), and prints one closing line
# "N passed, N failed, N skipped". Exits non-zero on any failure, on a test
# binary that produced no result, or when no test ran at all.
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:/bin:$PATH
# shellcheck disable=SC1091
set +u; source devel/setup.bash; set -u
export ROS_HOME=${ROS_HOME:-$PWD/build/ros_home}   # logs of test runs stay in the build tree
export BIOVISION_SHARED=${BIOVISION_SHARED:-$(cd .. && pwd)/shared}

rm -rf build/test_results
mkdir -p "$ROS_HOME"
log=build/run_tests.log
echo "run_tests: running gtests and rostests (log: $log)"
# Catkin's leaf targets, one per gtest binary or rostest file: _run_tests_<package>_<type>_<name>.
packages=$(for d in src/*/package.xml; do basename "$(dirname "$d")"; done | paste -sd'|')
mapfile -t leaves < <(make -s -C build help | sed -n 's/^\.\.\. \(_run_tests_.*\)$/\1/p' |
  grep -E "^_run_tests_($packages)_(gtest|rostest|roslaunch-check|nosetests)_" | sort)
# Two at a time, except the rostests below: each brings up its own master on a free port, and most wait on
# messages more than they compute. These run alone, one after another, because they drive the simulator or a
# bag through the perception graph at camera rate, or assert rates, latencies and deadlines that need both
# cores (running them side by side would test the machine, not the code).
alone='_rostest_test_(mission|closed_loop|tabletop_bag_nodes|tabletop_bag_nodelets|monitor_rviz|sim_recognition|head_loop|replay|euroc_replay|sim_node|robot_launch|persistence|greet_sim|greet_tasks_sim|memory_sim|topic_report_latency)\.test$'
mapfile -t paired < <(printf '%s\n' "${leaves[@]}" | grep -vE "$alone")
mapfile -t single < <(printf '%s\n' "${leaves[@]}" | grep -E "$alone")
logs=build/test_logs
rm -rf "$logs" && mkdir -p "$logs"
# A leaf's own rule from its build.make, as CMake's Makefile2 runs it: `make <leaf>` would first walk every
# target of the workspace (~28 s each time).
run_leaf() {
  local dir
  dir=$(cd build && echo */CMakeFiles/"$1".dir)
  make -s -C build -f "$dir/build.make" "$dir/build" >"$2/$1.log" 2>&1 || { echo "run_tests: $1 exited $?"; return 1; }
}
export -f run_leaf
build_rc=0
# shellcheck disable=SC2016  # $1 and $2 belong to the inner shell
printf '%s\n' "${paired[@]}" | xargs -P2 -I{} bash -c 'run_leaf "$1" "$2"' _ {} "$logs" || build_rc=1
for leaf in "${single[@]}"; do run_leaf "$leaf" "$logs" || build_rc=1; done
echo "run_tests: ${#leaves[@]} test targets, ${#paired[@]} two at a time and ${#single[@]} alone"
cat "$logs"/*.log >"$log"
if [[ ${#leaves[@]} -eq 0 ]]; then echo "run_tests: no test target found in build/"; build_rc=1; fi
grep -E '^\[ *(RUN|  *OK|  FAILED|  PASSED|  SKIPPED) *\]|^\[ROSTEST\]|^\[Testcase|FAILURE|Error' "$log" | grep -vE '^\[ +RUN' | tail -n 200 || true
# One rostest again from the install space (catkin_make install into install/); its results are in
# build/test_results/install_space/ and count below.
bash scripts/install_test.sh
install_rc=$?

/usr/bin/python3 scripts/test_summary.py build/test_results
summary_rc=$?
if [[ $build_rc -ne 0 ]]; then
  echo "run_tests: a test target failed (see $log and build/test_logs/)"
  exit 1
fi
if [[ $install_rc -ne 0 ]]; then
  echo "run_tests: scripts/install_test.sh exited $install_rc (see build/install_test.log)"
  exit 1
fi
exit $summary_rc
