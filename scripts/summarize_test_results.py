#!/usr/bin/env python3
"""Counts test cases in the JUnit XML files that catkin's run_tests leaves under build/test_results.

Prints every failed case, then `tests: N passed, M failed` and exits 1 when M > 0 or when no test ran.
A skipped case counts as neither passed nor failed and is listed as skipped.
rostest wrapper cases count only when they failed (see below).

With --programs FILE (ctest's --output-junit, one case a test program: scripts/check_core.sh), a
program's case counts where no result file of its name is under the root (a program that writes
none, such as a fuzz replay), or where it failed and its own file shows no failed case: the program
died outside a case (a leak found at exit) or before writing its file (a crash, a sanitizer report).
"""
import argparse
import pathlib
import sys
import xml.etree.ElementTree as ET


def failed_case(c):
    return c.find("failure") is not None or c.find("error") is not None


def main(root, programs=None):
    passed, failed, skipped, failures = 0, 0, 0, []
    files = sorted(pathlib.Path(root).rglob("*.xml"))
    if programs:
        by_name = {f.stem: f for f in files}
        for c in ET.parse(programs).getroot().iter("testcase"):
            own = by_name.get(c.get("name", ""))
            if own is None:
                if c.get("status") in ("notrun", "disabled"):
                    skipped += 1
                elif failed_case(c):
                    failed += 1
                    failures.append(f"{c.get('name')}: failed")
                else:
                    passed += 1
            elif failed_case(c) and not any(failed_case(k) for k in ET.parse(own).getroot().iter("testcase")):
                failed += 1
                failures.append(f"{c.get('name')}: the program failed outside its cases (a leak at exit?)")
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
            elif failed_case(c):
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
    parser = argparse.ArgumentParser(description="Counts the test cases of JUnit XML result files.")
    parser.add_argument("root", nargs="?", default=".", help="folder searched for *.xml")
    parser.add_argument("--programs", help="ctest --output-junit file, one case a test program")
    args = parser.parse_args()
    sys.exit(main(args.root, args.programs))
