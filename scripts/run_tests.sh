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
# -j1, one test after another: each rostest starts its own master on a free port, but the closed-loop ones
# (simulator + perception at camera rate) need both cores to keep their rates and deadlines.
make -C build run_tests -j1 >"$log" 2>&1
build_rc=$?
grep -E '^\[ *(RUN|  *OK|  FAILED|  PASSED|  SKIPPED) *\]|^\[ROSTEST\]|^\[Testcase|FAILURE|Error' "$log" | grep -vE '^\[ +RUN' | tail -n 200 || true
# One rostest again from the install space (catkin_make install into install/); its results are in
# build/test_results/install_space/ and count below.
bash scripts/install_test.sh
install_rc=$?

/usr/bin/python3 scripts/test_summary.py build/test_results
summary_rc=$?
if [[ $build_rc -ne 0 ]]; then
  echo "run_tests: 'make run_tests' exited $build_rc (see $log)"
  exit 1
fi
if [[ $install_rc -ne 0 ]]; then
  echo "run_tests: scripts/install_test.sh exited $install_rc (see build/install_test.log)"
  exit 1
fi
exit $summary_rc
