#!/usr/bin/env python3
"""Render a zline batch on a Ray cluster: one Ray task per shard.

Each task runs `zline batch INPUTS -o OUT --shard I/N` on whatever node Ray
gives it; OUT must be a folder every node sees (a shared file system). zline
writes each image atomically and skips images that exist, so a task whose
worker dies is simply run again by Ray (`max_retries`) and renders only what
is missing: nothing is lost and nothing is rendered twice to completion.

    pip install ray
    python3 docs/ray_batch.py --shards 8 -o renders/ models/*.obj
    python3 docs/ray_batch.py --address auto ...   # an existing cluster

Without --address, Ray starts a local cluster on this machine. The flags
after `--` go to `zline batch` as they are (e.g. `-- --size 640x480`).

--kill-first-attempt is for testing the recipe: the first attempt of shard 1
kills its zline process and its Ray worker once zline has written one image,
as a lost machine would; Ray then runs that shard again.
"""

import argparse
import os
import shutil
import signal
import subprocess
import sys
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("inputs", nargs="+", help="models or scene files (paths every node sees)")
    parser.add_argument("-o", "--output", required=True, help="output folder (shared by every node)")
    parser.add_argument("--shards", type=int, default=4, help="Ray tasks, one zline shard each")
    parser.add_argument("--zline", default=shutil.which("zline") or "zline", help="the zline binary")
    parser.add_argument("--address", default=None, help="a Ray cluster's address (default: a local one)")
    parser.add_argument("--retries", type=int, default=3, help="attempts after a worker dies")
    parser.add_argument("--kill-first-attempt", action="store_true", help=argparse.SUPPRESS)
    args, extra = parser.parse_known_args()
    extra = [a for a in extra if a != "--"]

    import ray

    ray.init(address=args.address, include_dashboard=False, log_to_driver=True)
    os.makedirs(args.output, exist_ok=True)
    marker = os.path.join(args.output, ".ray-batch-killed-once")

    @ray.remote(max_retries=args.retries)
    def shard(index):
        command = [args.zline, "batch", *args.inputs, "-o", args.output,
                   "--shard", f"{index}/{args.shards}", "--quiet", *extra]
        if args.kill_first_attempt and index == 1 and not os.path.exists(marker):
            open(marker, "w").close()
            before = set(os.listdir(args.output))
            child = subprocess.Popen(command)
            while child.poll() is None:
                written = {f for f in os.listdir(args.output) if f.endswith(".png")} - before
                if written:
                    child.send_signal(signal.SIGKILL)
                    child.wait()
                    print(f"shard {index}: killed after {sorted(written)}", flush=True)
                    os._exit(1)  # the worker dies; Ray runs the task again
                time.sleep(0.001)
        started = time.time()
        done = subprocess.run(command, capture_output=True, text=True)
        return index, done.returncode, done.stderr, time.time() - started

    failed = 0
    for index, code, stderr, seconds in ray.get([shard.remote(i) for i in range(1, args.shards + 1)]):
        print(f"shard {index}/{args.shards}: exit {code} in {seconds:.2f} s", flush=True)
        if stderr.strip():
            print(stderr.rstrip(), file=sys.stderr)
        failed += code != 0
    if os.path.exists(marker):
        os.remove(marker)
    ray.shutdown()
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
