"""Where the instabilities of a static-kinetic run happen (stdlib only).

Reads an events.csv (`tribofe slide`, `tribofe precursors --fe`) and prints, up to the end of the
first cycle (a whole-interface slip or a front crossing, or the end of the file):
the events by kind; the tip advances whose region lies inside the run already slipped from the
trailing edge (re-slips of healed nodes) against those that move the front on; the single-node
share; the peak F; and the front crossing, the first event after which the run of nodes slipped
since the start reaches the leading contact node, with its F and the precursors before it.

    python3 validation/precursors/chatter.py path/to/events.csv
"""
import csv
import statistics
import sys


def run_end(slipped):
    """Last node of the contiguous run of slipped nodes from the first one (-1: none)."""
    if not slipped:
        return -1
    end = min(slipped)
    while end + 1 in slipped:
        end += 1
    return end


def main(path):
    rows = list(csv.DictReader(open(path)))
    ends = sorted({float(r[k]) for r in rows for k in ("region_first_over_L", "region_last_over_L") if r[k]})
    h = min(b - a for a, b in zip(ends, ends[1:]) if b - a > 1e-12)
    node = lambda x: round((x + 0.5) / h)  # node index from the trailing edge (x = -1/2)
    last = max(node(x) for x in ends)
    kinds, sizes = {}, []
    inside = beyond = single = precursors = 0
    slipped = set()
    crossing = None
    ended = "the end of the file"
    f_peak = 0.0
    for r in rows:
        k = r["kind"]
        if k in ("sliding", "crossing"):
            ended = f"event {r['event']} ({k}, F/(mu_s N) = {float(r['F_over_mu_s_N']):.4f})"
            break
        kinds[k] = kinds.get(k, 0) + 1
        f_peak = max(f_peak, float(r["F_over_mu_s_N"]))
        if not r["region_first_over_L"]:
            continue
        a, b = node(float(r["region_first_over_L"])), node(float(r["region_last_over_L"]))
        sizes.append(b - a + 1)
        front = run_end(slipped)
        if k == "tip-advance":
            inside += b <= front
            beyond += b > front
            single += a == b
        precursors += k == "precursor"
        slipped.update(range(a, b + 1))
        if crossing is None and run_end(slipped) >= last:
            crossing = (r["event"], k, float(r["F_over_mu_s_N"]), precursors)
    print(f"{path}: first cycle ends at {ended}; events before it by kind: {kinds}")
    print(f"instability regions: median {statistics.median(sizes)} nodes, largest {max(sizes)}")
    print(f"tip advances inside the slipped run: {inside}, moving the front on: {beyond}; single-node: {single}")
    print(f"peak F/(mu_s N) before it: {f_peak:.4f}")
    if crossing:
        e, k, f, n = crossing
        print(f"front crossing at event {e} ({k}), F/(mu_s N) = {f:.4f}, after {n} precursors")
    elif "crossing" not in ended:
        print("no front crossing")


if __name__ == "__main__":
    main(sys.argv[1])
