"""Summarises JUnit XML files (gtest, rostest, rosunit) into 'N passed, N failed, N skipped'.

A result file whose name says MISSING (rosunit writes one when a test binary died before writing
its own) counts as a failure, and so does a run with no test at all."""
import pathlib
import sys
import xml.etree.ElementTree as ET


def main(root):
    passed = failed = skipped = 0
    failures = []
    files = sorted(pathlib.Path(root).rglob("*.xml")) if pathlib.Path(root).is_dir() else []
    for path in files:
        try:
            tree = ET.parse(path)
        except ET.ParseError as err:
            failed += 1
            failures.append(f"{path}: unreadable result ({err})")
            continue
        cases = tree.getroot().iter("testcase")
        for case in cases:
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                failures.append(f"{path.parent.name}: {name}")
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    for line in failures:
        print(f"FAILED: {line}")
    print(f"{passed} passed, {failed} failed, {skipped} skipped")
    if passed + failed == 0:
        print("no test ran")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build/test_results"))
