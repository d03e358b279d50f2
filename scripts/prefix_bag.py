#!/usr/bin/env python3
"""Copies a bag into its own namespace, so that several bags can play at once in one ROS graph.

Every topic /T becomes /PREFIX/T (except /tf and /tf_static, which are shared by all), every frame id
F (header.frame_id, child_frame_id, in any message and in tf) becomes PREFIX/F, and every time (the
record time and all stamps) is shifted so that the bag starts at --start_s and, with --duration_s,
scaled so that it lasts that long (a long run played faster beside short ones). The demo uses it to play
the field, laser, indoor and tracking runs side by side (launch/demo.launch).

Usage: prefix_bag.py --prefix NAME [--start_s T] [--duration_s D] INPUT.bag OUTPUT.bag
INPUT is only read; OUTPUT is written to a temporary file beside it and then renamed.
Needs the ROS Python modules (python3-rosbag, the project's messages from a sourced workspace);
run with /usr/bin/python3.
"""
import argparse
import os
import sys

import genpy
import rosbag

SHARED_TOPICS = ("/tf", "/tf_static")


def rewrite(msg, prefix, retime):
    """Prefixes frame ids and retimes stamps in msg and everything nested in it, in place."""
    for slot in getattr(msg, "__slots__", ()):
        value = getattr(msg, slot)
        if slot in ("frame_id", "child_frame_id") and isinstance(value, str) and value:
            setattr(msg, slot, prefix + "/" + value.lstrip("/"))
        elif isinstance(value, genpy.Time):
            if not value.is_zero():
                setattr(msg, slot, retime(value))
        elif isinstance(value, genpy.Message):
            rewrite(value, prefix, retime)
        elif isinstance(value, (list, tuple)) and value and isinstance(value[0], genpy.Message):
            for item in value:
                rewrite(item, prefix, retime)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--prefix", required=True, help="namespace and frame prefix, e.g. slam")
    parser.add_argument("--start_s", type=float, default=None,
                        help="time of the first message in the output (default: unchanged)")
    parser.add_argument("--duration_s", type=float, default=None,
                        help="length of the output in seconds (default: the input's)")
    parser.add_argument("input")
    parser.add_argument("output")
    args = parser.parse_args()
    prefix = args.prefix.strip("/")
    if not prefix:
        sys.exit("prefix_bag: --prefix must name a namespace")
    if os.path.abspath(args.input) == os.path.abspath(args.output):
        sys.exit("prefix_bag: output must differ from input (the input is never overwritten)")
    try:
        src = rosbag.Bag(args.input)
    except Exception as e:  # rosbag raises several unrelated types
        sys.exit("prefix_bag: %s: cannot read bag: %s" % (args.input, e))
    if args.duration_s is not None and args.duration_s <= 0:
        sys.exit("prefix_bag: --duration_s must be positive (got %g)" % args.duration_s)
    start = src.get_start_time()
    new_start = start if args.start_s is None else args.start_s
    length = src.get_end_time() - start
    scale = 1.0 if args.duration_s is None or length <= 0 else args.duration_s / length
    # Nanosecond arithmetic: a float of 1.6e9 s keeps only ~0.2 us, enough, but exact is as easy.
    start_ns = genpy.Time.from_sec(start).to_nsec()
    new_start_ns = genpy.Time.from_sec(new_start).to_nsec()

    def retime(t):
        out = type(t)()
        out.set(0, 0)
        ns = new_start_ns + int(round((t.to_nsec() - start_ns) * scale))
        out.secs, out.nsecs = divmod(ns, 1000000000)
        return out
    tmp = args.output + ".tmp"
    count = 0
    with rosbag.Bag(tmp, "w") as dst:
        for topic, msg, t, header in src.read_messages(return_connection_header=True):
            rewrite(msg, prefix, retime)
            if topic not in SHARED_TOPICS:
                topic = "/" + prefix + "/" + topic.lstrip("/")
            header = dict(header or {})
            header["topic"] = topic  # keeps the rest (latching, message definition)
            dst.write(topic, msg, retime(t), connection_header=header)
            count += 1
    src.close()
    os.replace(tmp, args.output)
    print("prefix_bag: %s -> %s: %d messages under /%s, frames %s/*" %
          (args.input, args.output, count, prefix, prefix))


if __name__ == "__main__":
    main()
