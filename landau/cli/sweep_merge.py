"""Join the shards of a sweep (landau sweep --shard I/N) into one netCDF file.

``landau sweep-merge OUT.nc SHARD.nc [SHARD.nc ...] [--json]``

Each point is taken from the shard that finished it; shards of different sweeps (another task,
model, law declaration, fixed parameters, task options or grid) are refused.  The summary gives,
per shard, its points and how many are finished, failed and pending, and the shards not given.
OUT.nc is written (atomically) whatever is missing: the same ``landau sweep`` command without
``--shard`` and with ``--out OUT.nc`` computes the points still pending.  Exit code 0 when every
point is finished, 1 when points are pending (a shard missing or unfinished), 2 for bad input.

Example::

    landau sweep hopf spring-block dieterich --grid V=1e-6:1e-3:600:log --grid a=0.01:0.04:300 \\
        --shard $SLURM_ARRAY_TASK_ID/8 --out kc.nc          # in each of the 8 jobs of an array
    landau sweep-merge kc.nc kc.shard-*-of-8.nc
"""

from __future__ import annotations


def configure(p) -> None:
    p.add_argument("out", metavar="OUT.nc", help="the merged netCDF file")
    p.add_argument("shards", nargs="*", metavar="SHARD.nc",
                   help="the shards' files (landau sweep --shard I/N); at least one")


def run(args) -> dict:
    from landau.analyses.sweep import merge

    _, report = merge(args.shards, args.out)
    return {"out": str(args.out), **report, "exit_code": 1 if report["pending"] else 0}


def render(doc: dict) -> str:
    lines = [f"merged {len(doc['files'])} file(s) into {doc['out']}: {doc['points']} points, "
             f"{doc['pending']} pending"]
    for f in doc["files"]:
        lines.append(f"  {f['file']}{' (shard ' + f['shard'] + ')' if f['shard'] else ''}: {f['points']} points, "
                     f"{f['finished']} finished, {f['failed']} failed, {f['pending']} pending")
    lines.extend(f"  shard {i}/{doc['shards']} missing" for i in doc["missing_shards"])
    lines.append("  status: " + ", ".join(f"{k}: {n}" for k, n in doc["status"].items()))
    return "\n".join(lines)
