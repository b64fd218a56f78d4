#!/usr/bin/python3
"""Times the basis stage (`offsetopt basis`, k = 36) on icospheres of about 10k, 40k and 160k
vertices and, where SciPy is installed, ARPACK (scipy.sparse.linalg.eigsh in shift-invert mode,
the paper's choice) on exactly the same matrices, shift, k and tolerance.

usage: bench/spectral/bench_basis.py [--sizes 5,6,7] [--k 36] [--basis mass|laplacian]
                                     [--tol 1e-10] [--binary build/offsetopt] [--no-arpack]

Printed per size: our solve seconds (ordering + factorisation + iterations, from the JSON
report's "seconds"; reading and assembly excluded), the factorisation part, total seconds of
the command, peak memory (/usr/bin/time -v, whole process), operator applications; ARPACK's
seconds (eigsh alone: SuperLU factorisation + iterations, reading excluded) and peak memory;
the ratio ours/ARPACK; the largest eigenvalue difference relative to the k-th eigenvalue; and the
largest residual |L phi - lambda M phi| / (|L|inf |phi|) of each solver's pairs.

Run it on a quiet machine, once: it takes about a minute for the three sizes (ARPACK's 160k run
dominates). The machine load (uptime) is printed with the figures.
Use /usr/bin/python3: it must be the interpreter that sees Debian's python3-scipy.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import icosphere  # noqa: E402


def peak_kib(time_v_stderr):
    match = re.search(r"Maximum resident set size \(kbytes\): (\d+)", time_v_stderr)
    return int(match.group(1)) if match else -1


def run_ours(binary, mesh, k, basis, tol, prefix, report):
    command = ["/usr/bin/time", "-v", binary, "basis", mesh, "--k", str(k), "--basis", basis,
               "--tol", repr(tol), "--json", report, "--matrices", prefix, "--quiet"]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode not in (0, 3):
        sys.exit("offsetopt failed:\n" + done.stderr)
    with open(report) as f:
        result = json.load(f)
    result["peak_kib"] = peak_kib(done.stderr)
    return result


def arpack_worker(prefix, k, tol, sigma, basis, out):
    """Runs in its own process (under /usr/bin/time -v) so its peak memory is its own."""
    import numpy as np
    import scipy.io
    import scipy.sparse.linalg
    L = scipy.io.mmread(prefix + "_L.mtx").tocsc()
    M = scipy.io.mmread(prefix + "_M.mtx").tocsc() if basis == "mass" else None
    start = time.perf_counter()
    values, vectors = scipy.sparse.linalg.eigsh(L, k=k, M=M, sigma=sigma, which="LM", tol=tol)
    seconds = time.perf_counter() - start
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    norm = abs(L).sum(axis=1).max()
    mass = M.diagonal() if M is not None else np.ones(L.shape[0])
    residuals = [float(np.linalg.norm(L @ vectors[:, j] - values[j] * mass * vectors[:, j]) /
                       (norm * np.linalg.norm(vectors[:, j]))) for j in range(k)]
    with open(out, "w") as f:
        json.dump({"seconds": seconds, "eigenvalues": values.tolist(), "residuals": residuals}, f)


def run_arpack(prefix, k, tol, sigma, basis, out):
    command = ["/usr/bin/time", "-v", sys.executable, os.path.abspath(__file__), "--arpack-worker",
               prefix, str(k), repr(tol), repr(sigma), basis, out]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        print("ARPACK failed: " + done.stderr.strip().splitlines()[0] if done.stderr else "ARPACK failed")
        return None
    with open(out) as f:
        result = json.load(f)
    result["peak_kib"] = peak_kib(done.stderr)
    return result


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--arpack-worker":
        prefix, k, tol, sigma, basis, out = sys.argv[2:8]
        arpack_worker(prefix, int(k), float(tol), float(sigma), basis, out)
        return
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", default="5,6,7", help="icosphere subdivisions (5: 10242, 6: 40962, 7: 163842 vertices)")
    parser.add_argument("--k", type=int, default=36)
    parser.add_argument("--basis", default="mass", choices=["mass", "laplacian"])
    parser.add_argument("--tol", type=float, default=1e-10)
    parser.add_argument("--binary", default=os.path.join(HERE, "..", "..", "build", "offsetopt"))
    parser.add_argument("--no-arpack", action="store_true")
    args = parser.parse_args()
    have_scipy = False
    if not args.no_arpack:
        try:
            import scipy.sparse.linalg  # noqa: F401
            have_scipy = True
        except ImportError:
            print("SciPy not found: timing ours only")
    print("load before:", os.getloadavg(), "cpus:", os.cpu_count())
    header = ("vertices", "ours s", "factor s", "total s", "peak MB", "ops", "ARPACK s", "peak MB", "ours/ARPACK",
              "max |dlambda|/lambda_k", "max res ours", "max res ARPACK")
    rows = []
    with tempfile.TemporaryDirectory(prefix="offsetopt_bench_") as tmp:
        for s in [int(x) for x in args.sizes.split(",")]:
            mesh = os.path.join(tmp, "ico%d.obj" % s)
            V, F = icosphere.icosphere(s)
            icosphere.write_obj(mesh, V, F)
            prefix = os.path.join(tmp, "ico%d" % s)
            ours = run_ours(args.binary, mesh, args.k, args.basis, args.tol, prefix, prefix + ".json")
            row = [ours["vertices"], "%.3f" % ours["seconds"], "%.3f" % ours["factor_seconds"],
                   "%.3f" % ours["total_seconds"], "%.0f" % (ours["peak_kib"] / 1024), ours["operator_applications"]]
            arpack = None
            if have_scipy:
                arpack = run_arpack(prefix, args.k, args.tol, -ours["shift"], args.basis, prefix + "_arpack.json")
            if arpack:
                lam_k = max(abs(ours["eigenvalues"][-1]), 1e-300)
                diff = max(abs(a - b) for a, b in zip(ours["eigenvalues"], arpack["eigenvalues"])) / lam_k
                row += ["%.3f" % arpack["seconds"], "%.0f" % (arpack["peak_kib"] / 1024),
                        "%.3f" % (ours["seconds"] / arpack["seconds"]), "%.1e" % diff,
                        "%.1e" % max(ours["residuals"]), "%.1e" % max(arpack["residuals"])]
            else:
                row += ["-"] * 5 + ["%.1e" % max(ours["residuals"])]
            rows.append(row)
            print("  done %d vertices (status %s)" % (ours["vertices"], ours["status"]), flush=True)
    print("load after:", os.getloadavg())
    print("basis %s, k = %d, tol = %g" % (args.basis, args.k, args.tol))
    widths = [max(len(str(h)), *(len(str(r[i])) if i < len(r) else 1 for r in rows)) for i, h in enumerate(header)]
    print("  ".join(str(h).rjust(w) for h, w in zip(header, widths)))
    for r in rows:
        print("  ".join(str(c).rjust(w) for c, w in zip(r, widths)))


if __name__ == "__main__":
    main()
