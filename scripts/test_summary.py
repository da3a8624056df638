"""Summarises JUnit XML files (gtest, rostest, rosunit) into 'N passed, N failed, N skipped'.

A result file whose name says MISSING (rosunit writes one when a test binary died before writing
its own) counts as a failure, and so does a run with no test at all. Each failure is printed with
its message and, for a rostest, the lines of its captured output that say how the test process
ended (died with a signal, timed out, no results): CI shows only the tail of make test's output,
so the cause has to be there, next to the summary line."""
import glob
import pathlib
import re
import sys
import xml.etree.ElementTree as ET

DETAIL_LINES = 12
LOG_TAIL_LINES = 15
# What rostest/roslaunch print when a test process ends badly.
ENDING = re.compile(r"process has died|exit code|timed out|max time|time limit|did not generate|"
                    r"Traceback|Error|FAILED|Failure", re.IGNORECASE)


def details(case, out):
    """The failure's message and text, then the telling lines of the result file's captured output `out`
    (rostest puts it beside the test cases, not inside them) and the tail of the log it names."""
    lines = []
    for tag in ("failure", "error"):
        for node in case.findall(tag):
            if node.get("message"):
                lines.append(node.get("message"))
            lines += (node.text or "").strip().splitlines()
    lines += [line for line in out.splitlines() if ENDING.search(line)]
    lines = [strip(line) for line in lines if line.strip()]
    if len(lines) > DETAIL_LINES:
        lines = lines[:DETAIL_LINES] + [f"... ({len(lines) - DETAIL_LINES} more lines in the result file)"]
    # The test process's own output (which gtest case ran last, its messages) is in the log rostest names.
    for pattern in re.findall(r"log file: (\S+)", strip(out)):
        for log in sorted(glob.glob(pattern)):
            tail = pathlib.Path(log).read_text(errors="replace").splitlines()[-LOG_TAIL_LINES:]
            lines.append(f"last {len(tail)} lines of {log}:")
            lines += ["  " + strip(line) for line in tail]
    return lines


def strip(line):
    # Colour codes, raw or as rostest escapes them ("&#x001B;[0m").
    return re.sub(r"(\x1b|&#x001B;)\[[0-9;]*m", "", line).strip()


def main(root):
    passed = failed = skipped = 0
    failures = []
    files = sorted(pathlib.Path(root).rglob("*.xml")) if pathlib.Path(root).is_dir() else []
    for path in files:
        try:
            tree = ET.parse(path)
        except ET.ParseError as err:
            failed += 1
            failures.append((f"{path}: unreadable result ({err})", []))
            continue
        out = "\n".join(n.text or "" for n in tree.getroot().iter() if n.tag in ("system-out", "system-err"))
        for case in tree.getroot().iter("testcase"):
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                failures.append((f"{path.parent.name}: {name} ({path.name})", details(case, out)))
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    for title, lines in failures:
        print(f"FAILED: {title}")
        for line in lines:
            print(f"    {line}")
    print(f"{passed} passed, {failed} failed, {skipped} skipped")
    if passed + failed == 0:
        print("no test ran")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build/test_results"))
