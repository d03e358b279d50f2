#!/usr/bin/python3
"""scripts/prefix_bag.py on the bundled office laser bag: topics and frames move into the namespace,
stamps are shifted and scaled exactly, /tf stays shared, the input is never written, and a bad
call fails with a message naming what was wrong. Run by test/ros/prefix_bag.test (rostest)."""
import hashlib
import os
import subprocess
import sys
import tempfile
import unittest

import rosbag
import rosunit

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "prefix_bag.py")
BAG = os.path.join(ROOT, "rosbag", "laser_office.bag")


def md5(path):
    with open(path, "rb") as f:
        return hashlib.md5(f.read()).hexdigest()


def frame_ids(msg):
    """Every frame_id / child_frame_id in msg, nested ones included."""
    out = []
    for slot in getattr(msg, "__slots__", ()):
        value = getattr(msg, slot)
        if slot in ("frame_id", "child_frame_id") and isinstance(value, str) and value:
            out.append(value)
        elif hasattr(value, "__slots__"):
            out += frame_ids(value)
        elif isinstance(value, list) and value and hasattr(value[0], "__slots__"):
            for item in value:
                out += frame_ids(item)
    return out


class PrefixBagTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="prefix_bag_test")
        self.out = os.path.join(self.dir, "out.bag")

    def run_script(self, *args):
        return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True)

    def test_topics_frames_and_times(self):
        before = md5(BAG)
        # The office bag lasts 30 s from 1600000000; the copy starts 100 s later and lasts 15 s.
        r = self.run_script("--prefix", "slam", "--start_s", "1600000100", "--duration_s", "15",
                            BAG, self.out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(md5(BAG), before, "the input bag was modified")
        src, dst = rosbag.Bag(BAG), rosbag.Bag(self.out)
        s0 = src.get_start_time()
        self.assertAlmostEqual(dst.get_start_time(), 1600000100.0, places=6)
        self.assertAlmostEqual(dst.get_end_time() - dst.get_start_time(),
                               15.0, places=6)
        pairs = list(zip(src.read_messages(), dst.read_messages()))
        self.assertEqual(len(pairs), src.get_message_count())
        self.assertEqual(dst.get_message_count(), src.get_message_count())
        for (t_in, m_in, r_in), (t_out, m_out, r_out) in pairs:
            if t_in in ("/tf", "/tf_static"):
                self.assertEqual(t_out, t_in)
            else:
                self.assertEqual(t_out, "/slam" + t_in)
            # Frames: the same list with the prefix in front.
            self.assertEqual(frame_ids(m_out), ["slam/" + f.lstrip("/") for f in frame_ids(m_in)])
            # Times: t' = 1600000100 + (t - s0) / 2, to the nanosecond (rounding).
            expect = 1600000100.0 + (r_in.to_sec() - s0) * 0.5
            self.assertAlmostEqual(r_out.to_sec(), expect, delta=2e-9 + 1e-6)
            if hasattr(m_in, "header") and not m_in.header.stamp.is_zero():
                expect = 1600000100.0 + (m_in.header.stamp.to_sec() - s0) * 0.5
                self.assertAlmostEqual(m_out.header.stamp.to_sec(), expect, delta=1e-6)
        scans = [m for t, m, _ in dst.read_messages(topics=["/slam/scan"])]
        self.assertEqual(len(scans), 301)
        self.assertEqual(scans[0].header.frame_id, "slam/laser")
        # The static transform keeps its latching, so late subscribers still get it.
        conns = [c for c in dst._get_connections(topics=["/tf_static"])]
        self.assertTrue(conns and conns[0].header.get("latching") in (b"1", "1"))

    def test_bad_calls_fail_and_leave_files_alone(self):
        before = md5(BAG)
        r = self.run_script("--prefix", "x", BAG, BAG)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("output must differ from input", r.stderr)
        r = self.run_script("--prefix", "x", "--duration_s", "-1", BAG, self.out)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("--duration_s must be positive", r.stderr)
        self.assertFalse(os.path.exists(self.out))
        bad = os.path.join(self.dir, "not_a_bag.bag")
        with open(bad, "w") as f:
            f.write("hello\n")
        r = self.run_script("--prefix", "x", bad, self.out)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("cannot read bag", r.stderr)
        self.assertEqual(md5(BAG), before)
        self.assertFalse(os.path.exists(self.out))


if __name__ == "__main__":
    rosunit.unitrun("adaptive_perception", "prefix_bag", PrefixBagTest)
