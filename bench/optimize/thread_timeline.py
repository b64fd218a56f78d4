"""Per-thread timeline from `perf script -F tid,time,ip,sym` lines (see thread_timeline.sh):
for each bucket of STEP seconds, each thread's sample count and its most sampled function."""
import collections
import re
import sys


def main(path, step):
    rows = []
    for line in open(path):
        m = re.match(r"\s*(\d+)\s+([\d.]+):\s+\S+\s+(.*)", line)
        if m:
            rows.append((int(m.group(1)), float(m.group(2)), m.group(3).strip()))
    if not rows:
        print("no samples")
        return
    start = min(r[1] for r in rows)
    buckets = collections.defaultdict(lambda: collections.defaultdict(collections.Counter))
    threads = sorted(set(r[0] for r in rows))
    for tid, t, symbol in rows:
        symbol = re.sub(r"\(anonymous namespace\)::", "", symbol)
        symbol = re.sub(r"\(.*", "", symbol)[-60:]
        buckets[int((t - start) / step)][tid][symbol] += 1
    for k in sorted(buckets):
        line = f"{k * step:5.2f}"
        for tid in threads:
            counts = buckets[k].get(tid)
            if counts:
                symbol, _ = counts.most_common(1)[0]
                line += f" | {tid % 1000:3d} {sum(counts.values()):3d} {symbol[:45]:45}"
        print(line)


if __name__ == "__main__":
    main(sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 0.025)
