"""Runs the shards of a waam sweep on a dask.distributed cluster (`waam sweep --dask ADDRESS` starts this).

Each run of the sweep is one Dask task: the worker runs `waam sweep FILE --shard K/N` into a temporary folder and
sends the shard's folder back as a tar archive, which is unpacked into OUT/shard_K here; `waam sweep` then merges
the shards (`waam bench --merge`) into one bench folder. Workers run `waam` in this process's folder and need the
same `waam` and the sweep's files at the same paths (a shared file system, or the same installation, data and
folders on every node); results come back over Dask,
so the output folder need not be shared. A shard folder that holds a finished bench.json is kept (resume).

Exit codes: 0 every shard ran (a shard whose runs did not all end as expected counts as ran: the merge reports it),
2 the scheduler does not answer or a shard could not run (one line, on stderr or into --error-file), 130
interrupted.
"""
import argparse
import io
import os
import subprocess
import sys
import tarfile
import tempfile


def run_shard(waam, sweep, cwd, index, count, threads, overrides, fresh):
    """On a worker: runs shard index/count of the sweep in folder cwd; returns (index, exit code, last log line,
    tar bytes)."""
    with tempfile.TemporaryDirectory(prefix="waam_dask_") as tmp:
        out = os.path.join(tmp, "shard")
        args = [waam, "sweep", sweep, "--shard", f"{index}/{count}", "--threads", str(threads), "-q", "-o", out]
        for o in overrides:
            args += ["--set", o]
        if fresh:
            args.append("--fresh")
        done = subprocess.run(args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              check=False)
        lines = [l for l in done.stdout.splitlines() if l.strip()]
        buffer = io.BytesIO()
        if os.path.isdir(out):
            with tarfile.open(fileobj=buffer, mode="w") as tar:
                tar.add(out, arcname=".")
        return index, done.returncode, (lines[-1] if lines else ""), buffer.getvalue()


def report_error(args, message):
    """The one line that says why the sweep did not run: into --error-file (waam prints it), else on stderr."""
    if args.error_file:
        with open(args.error_file, "w", encoding="utf-8") as f:
            f.write(message + "\n")
    else:
        print(message, file=sys.stderr)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scheduler", required=True, help="the Dask scheduler's address, e.g. tcp://127.0.0.1:8786")
    parser.add_argument("--waam", required=True, help="path of the waam executable on the workers")
    parser.add_argument("--sweep", required=True, help="the sweep file, relative to --cwd or absolute")
    parser.add_argument("--cwd", default=os.getcwd(), help="the folder the workers run waam in (default: this one)")
    parser.add_argument("--shards", type=int, required=True, help="number of shards (one Dask task each)")
    parser.add_argument("--threads", type=int, default=1, help="--threads of each shard's waam")
    parser.add_argument("--out", required=True, help="folder for shard_0 .. shard_{N-1}")
    parser.add_argument("--set", action="append", default=[], help="key.path=value of every run")
    parser.add_argument("--fresh", action="store_true", help="rerun shards that are already complete")
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds to wait for the scheduler")
    parser.add_argument("--error-file", help="write the one-line reason of a failure here instead of stderr")
    parser.add_argument("--quiet", action="store_true", help="no progress lines")
    a = parser.parse_args()
    try:
        from distributed import Client, as_completed
    except ImportError as e:
        report_error(a, f"dask.distributed is not installed ({e}): apt-get install python3-distributed")
        return 2
    try:
        client = Client(a.scheduler, timeout=a.timeout)
    except (OSError, TimeoutError) as e:
        reason = str(e).splitlines()[0] if str(e) else type(e).__name__
        report_error(a, f"--dask {a.scheduler}: the scheduler does not answer within {a.timeout:g} s ({reason})")
        return 2
    try:
        todo = [k for k in range(a.shards)
                if a.fresh or not os.path.isfile(os.path.join(a.out, f"shard_{k}", "bench.json"))]
        futures = [client.submit(run_shard, a.waam, a.sweep, a.cwd, k, a.shards, a.threads, a.set, a.fresh,
                                 key=f"waam-shard-{k}-of-{a.shards}", pure=False) for k in todo]
        for n, future in enumerate(as_completed(futures), 1):
            index, code, last, archive = future.result()
            if code not in (0, 3) or not archive:
                report_error(a, f"--dask {a.scheduler}: shard {index}/{a.shards} failed on its worker "
                                f"(exit {code}): {last}")
                return 2
            target = os.path.join(a.out, f"shard_{index}")
            partial = target + ".part"
            os.makedirs(partial, exist_ok=True)
            with tarfile.open(fileobj=io.BytesIO(archive), mode="r") as tar:
                tar.extractall(partial)
            if os.path.isdir(target):
                subprocess.run(["rm", "-rf", target], check=True)
            os.rename(partial, target)
            if not a.quiet:
                print(f"dask: shard {index}/{a.shards} done ({n}/{len(todo)})", file=sys.stderr)
    except KeyboardInterrupt:
        return 130
    finally:
        client.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
