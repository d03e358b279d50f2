#!/usr/bin/env python3
"""Counts test cases in the JUnit XML files that catkin's run_tests leaves under build/test_results.

Prints every failed case, then `tests: N passed, M failed` and exits 1 when M > 0 or when no test ran.
A skipped case counts as neither passed nor failed and is listed as skipped.
rostest wrapper cases count only when they failed (see below).
"""
import pathlib
import sys
import xml.etree.ElementTree as ET


def main(root):
    passed, failed, skipped, failures = 0, 0, 0, []
    files = sorted(pathlib.Path(root).rglob("*.xml"))
    for f in files:
        try:
            tree = ET.parse(f)
        except ET.ParseError as e:
            failed += 1
            failures.append(f"{f.name}: unreadable result file ({e})")
            continue
        cases = list(tree.getroot().iter("testcase"))
        if not cases:
            # rostest writes a suite with errors="1" and no cases when the launch itself failed.
            suite = tree.getroot()
            if int(suite.get("errors", 0) or 0) + int(suite.get("failures", 0) or 0) > 0:
                failed += 1
                failures.append(f"{f.name}: test did not run")
            continue
        # rostest writes a wrapper file (rostest-*.xml) with one case per test node, beside the node's own
        # results (rosunit-*.xml). Count the wrapper only when it failed (e.g. the node crashed or timed
        # out before writing results), so that a passing node is not counted twice.
        wrapper = f.name.startswith("rostest-")
        for c in cases:
            if wrapper and c.find("failure") is None and c.find("error") is None:
                continue
            name = f"{c.get('classname', '')}.{c.get('name', '')}"
            if c.find("skipped") is not None or c.get("status") == "notrun":
                skipped += 1
                print(f"  skipped: {name}")
            elif c.find("failure") is not None or c.find("error") is not None:
                failed += 1
                node = c.find("failure") if c.find("failure") is not None else c.find("error")
                msg = (node.get("message") or node.text or "").strip().splitlines()
                failures.append(f"{name}: {msg[0] if msg else ''}")
            else:
                passed += 1
    for f in failures:
        print(f"  FAILED: {f}")
    line = f"tests: {passed} passed, {failed} failed"
    if skipped:
        line += f", {skipped} skipped"
    print(line)
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
