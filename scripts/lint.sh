#!/usr/bin/env bash
# `make lint`: static checks. catkin_lint and clang-format read a fresh clone of HEAD in a temporary
# folder, not this working tree: a folder that exists only on this disk (git keeps no empty folders,
# so an install(DIRECTORY) of one breaks every fresh clone) or a file never committed is caught here
# as CI would catch it. Uncommitted changes are therefore not linted: commit first.
#  1. catkin_lint -W1 --strict over the clone's src/.
#  2. ROS-free cores (DESIGN §2): no core library of an algorithm package, devel/lib/lib<pkg>.so or
#     lib<pkg>_<name>.so (not the *_nodelet or *_ros wrappers, nor *_rviz plugins), may have a NEEDED entry for libroscpp,
#     librosconsole, libcv_bridge or libnodelet (readelf -d), nor name one on its link line
#     (build/<pkg>/CMakeFiles/<lib>.dir/link.txt). Both, because this machine's gcc links with
#     --as-needed by default: a core that links ${catkin_LIBRARIES} without calling ROS gets no NEEDED
#     entry, yet passes ROS on to everything that links it through CMake. Reads this workspace's
#     build/ and devel/ (make lint builds first); every package of src/ with such a library is
#     checked, future ones included, except the packages that are ROS code by design (ROS_PACKAGES).
#  3. clang-format --dry-run --Werror with the root .clang-format over the clone's C++ files: fails when
#     any file differs (format with `clang-format -i FILE`).
# Exits non-zero when a check fails; prints one line per check.
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:/bin:$PATH
ROS_PACKAGES="biovision_ros_common"   # shared ROS code: links roscpp on purpose
FORBIDDEN='lib(roscpp|rosconsole|cv_bridge|nodelet)'
status=0

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
head=$(git rev-parse HEAD)
git clone -q --no-checkout "$PWD" "$tmp/ws" && git -C "$tmp/ws" checkout -q "$head" || { echo "lint: cannot clone HEAD"; exit 1; }
[[ -z "$(git status --porcelain --untracked-files=no)" ]] || echo "lint: note: uncommitted changes are not linted (HEAD ${head:0:7})"

# 1. catkin_lint
if catkin_lint -W1 --strict "$tmp/ws/src" >"$tmp/catkin_lint.log" 2>&1; then
  echo "lint: catkin_lint -W1 --strict: no problems ($(tail -n 1 "$tmp/catkin_lint.log" | sed 's/^catkin_lint: //'))"
else
  grep -v "rosdep" "$tmp/catkin_lint.log"
  echo "lint: catkin_lint FAILED"
  status=1
fi

# 2. ROS-free core libraries
checked=0 bad=0
for xml in src/*/package.xml; do
  pkg=$(sed -n 's:.*<name>\(.*\)</name>.*:\1:p' "$xml" | head -n 1)
  [[ " $ROS_PACKAGES " == *" $pkg "* ]] && continue
  for lib in devel/lib/lib"$pkg".so devel/lib/lib"$pkg"_*.so; do
    [[ -f "$lib" && "$lib" != *_nodelet.so && "$lib" != *_ros.so && "$lib" != *_rviz.so ]] || continue  # ROS wrappers, rviz plugins
    checked=$((checked + 1))
    needed=$(readelf -d "$lib" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | grep -E "^$FORBIDDEN" | tr '\n' ' ')
    target=$(basename "$lib" .so)
    link="build/$pkg/CMakeFiles/${target#lib}.dir/link.txt"
    linked=""
    [[ -f "$link" ]] && linked=$(tr ' ' '\n' <"$link" | sed -n -E "s:.*/($FORBIDDEN[^/]*\.so).*:\1:p; s:^-l(roscpp|rosconsole|cv_bridge|nodelet.*)$:lib\1:p" | sort -u | tr '\n' ' ')
    if [[ -n "$needed" || -n "$linked" ]]; then
      echo "lint: ROS-free core $lib: NEEDED [${needed% }], link line [${linked% }]"
      bad=$((bad + 1))
    fi
  done
done
if ((checked == 0)); then
  echo "lint: no core library in devel/lib (build first: make build)"
  status=1
elif ((bad > 0)); then
  echo "lint: ROS-free cores FAILED: $bad of $checked core libraries link ROS"
  status=1
else
  echo "lint: ROS-free cores: $checked core libraries, none links ROS"
fi

# 3. clang-format
mapfile -t sources < <(git -C "$tmp/ws" ls-files '*.cpp' '*.hpp' '*.h' '*.cc')
differ=0
for f in "${sources[@]}"; do
  clang-format --dry-run --Werror "$tmp/ws/$f" >/dev/null 2>&1 || differ=$((differ + 1))
done
if ((differ == 0)); then
  echo "lint: clang-format: all ${#sources[@]} C++ files formatted"
else
  echo "lint: clang-format FAILED: $differ of ${#sources[@]} C++ files differ from .clang-format (clang-format -i FILE)"
  status=1
fi
exit $status
