#!/usr/bin/env python3
"""The CLI mutant pass (tests/fuzz/README.md): mutated copies of the files a user gives
h4cal and h4cam (robot.yaml, the dataset, the result JSON, camera and board YAML), each run
through the commands that read them, as a user would. A finding is a run killed by a signal,
a run over the time limit (a hang), or a run that answers (exit 0, or 3: a result judged
not good) with NaN or Inf in its output or in a file it wrote. A refusal (exit 1 with a message) is the expected outcome of
a bad file; a refusal may quote the bad value.

    tests/fuzz/cli_mutants.py --h4cal BUILD/host/h4cal --h4cam BUILD/firmware/h4cam \\
        [--mutants 2000] [--jobs 2] [--timeout 10] [--seed 1] [--work DIR]

Needs python3 (Debian python3-minimal). Prints one line per finding and a summary; exit 1
when there is a finding. The seeds are made fresh: a simulated Model 31 campaign with its
corners (h4cal simulate), its Model 12 result, and the repository's camera and board files.
"""
import argparse
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BOARDS = os.path.join(ROOT, "boards")
NON_FINITE = re.compile(rb"(?<![A-Za-z_])[-+]?(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)
SPECIAL_NUMBERS = ["1e308", "-1e308", "1e154", "-1e154", "nan", "inf", "-inf", "0", "-0",
                   "1e-320", "-1", "4294967297", "9223372036854775808", "1e9", "0.0000001", ""]


def mutate(text, rng):
    """One to three edits of a text file: a number replaced by a special one, a byte
    changed, a line dropped or doubled, the file cut, CRLF or a BOM."""
    data = bytearray(text)
    for _ in range(rng.randint(1, 3)):
        kind = rng.randrange(7)
        if kind <= 2:
            numbers = list(re.finditer(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?", bytes(data)))
            if numbers:
                m = rng.choice(numbers)
                data[m.start():m.end()] = rng.choice(SPECIAL_NUMBERS).encode()
        elif kind == 3 and data:
            i = rng.randrange(len(data))
            data[i] = rng.choice(b"\x00\xff\n\r,:#[]{}\"' -.e9")
        elif kind == 4:
            lines = bytes(data).split(b"\n")
            i = rng.randrange(len(lines))
            if rng.random() < 0.5:
                del lines[i]
            else:
                lines.insert(i, lines[i])
            data = bytearray(b"\n".join(lines))
        elif kind == 5 and data:
            data = data[:rng.randrange(len(data))]
        else:
            data = bytearray(b"\xef\xbb\xbf" + bytes(data).replace(b"\n", b"\r\n")
                             if rng.random() < 0.5 else bytes(data).replace(b"\n", b"\r\n"))
    return bytes(data)


def run(cmd, timeout, out_files):
    """(verdict, detail): 'ok', 'refused', or a finding ('signal', 'hang', 'non-finite')."""
    for f in out_files:
        if os.path.exists(f):
            os.remove(f)
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "hang", f"over {timeout} s"
    if p.returncode < 0 or p.returncode >= 128:
        return "signal", f"exit {p.returncode}: {p.stderr[-300:].decode(errors='replace')}"
    if p.returncode not in (0, 3):  # 3: a result that says "not good" (h4cal's exit codes)
        return "refused", ""
    outputs = [("stdout", p.stdout), ("stderr", p.stderr)]
    for f in out_files:
        if os.path.exists(f) and os.path.isfile(f):
            with open(f, "rb") as fh:
                outputs.append((f, fh.read()))
    for name, data in outputs:
        m = NON_FINITE.search(data)
        if m:
            line = data[max(0, data.rfind(b"\n", 0, m.start()) + 1):m.end() + 60]
            return "non-finite", f"{name}: {line.decode(errors='replace')}"
    return "ok", ""


def make_seeds(h4cal, h4cam, work):
    sim = os.path.join(work, "sim")
    subprocess.run([h4cal, "simulate", "--truth", "31", "--seed", "3", "--robot-seed", "3",
                    "--board", os.path.join(BOARDS, "aprilgrid_6x6_30mm.yaml"),
                    "--camera", os.path.join(BOARDS, "sim_camera_1024x768.yaml"),
                    "--out-dir", sim], check=True, capture_output=True)
    result = os.path.join(work, "result12.json")
    p = subprocess.run([h4cal, "identify", "--robot", os.path.join(sim, "robot.yaml"), "--data",
                        os.path.join(sim, "dataset.csv"), "--model", "12", "--out", result],
                       capture_output=True)
    if p.returncode not in (0, 3):
        sys.exit("cli_mutants: the seed identification failed: " + p.stderr.decode()[-300:])
    joints = os.path.join(work, "joints.csv")
    with open(os.path.join(sim, "dataset.csv")) as f, open(joints, "w") as j:
        rows = f.read().splitlines()
        head = rows[0].split(",")
        cols = [head.index(c) for c in ("pose_id", "q1", "q2", "q3", "q4")]
        for r in rows[:11]:
            cells = r.split(",")
            j.write(",".join(cells[c] for c in cols) + "\n")
    frames = os.path.join(work, "frames")
    subprocess.run([h4cam, "render", "--board", os.path.join(BOARDS, "aprilgrid_6x6_30mm.yaml"),
                    "--camera", os.path.join(BOARDS, "sim_camera_1024x768.yaml"), "--pose",
                    "0.01", "-0.02", "0.5", "1", "0", "0", "0", "--frames", "2", "--out-dir", frames],
                   check=True, capture_output=True)
    return {"robot": os.path.join(sim, "robot.yaml"), "data": os.path.join(sim, "dataset.csv"),
            "result": result, "joints": joints, "corners": os.path.join(sim, "corners.csv"),
            "camera": os.path.join(BOARDS, "sim_camera_1024x768.yaml"),
            "board": os.path.join(BOARDS, "aprilgrid_6x6_30mm.yaml"),
            "frames": frames}


def commands(kind, mutant, seeds, h4cal, h4cam, out):
    """The commands that read a mutated file of `kind`, and the files they write."""
    s = dict(seeds)
    s[kind] = mutant
    o = os.path.join(out, "out")
    fk = [h4cal, "fk", "--joints", s["joints"], "--out", o]
    if kind == "robot":
        return [(fk + ["--robot", s["robot"]], [o]),
                ([h4cal, "analyze", "--robot", s["robot"], "--data", s["data"]], []),
                ([h4cal, "identify", "--robot", s["robot"], "--data", s["data"], "--model", "12",
                  "--no-polish", "--folds", "2", "--out", o], [o])]
    if kind == "data":
        return [([h4cal, "check", "--result", s["result"], "--data", s["data"]], []),
                ([h4cal, "analyze", "--robot", s["robot"], "--data", s["data"]], []),
                ([h4cal, "identify", "--robot", s["robot"], "--data", s["data"], "--model", "12",
                  "--no-polish", "--folds", "2", "--out", o], [o])]
    if kind == "result":
        return [(fk + ["--result", s["result"]], [o]),
                ([h4cal, "check", "--result", s["result"], "--data", s["data"]], []),
                ([h4cal, "export", "--result", s["result"], "--out", o], [o])]
    if kind == "camera":
        return [([h4cal, "validate", "--robot", s["robot"], "--data", s["data"], "--result12",
                  s["result"], "--corners", s["corners"], "--board", s["board"], "--camera",
                  s["camera"]], []),
                ([h4cam, "measure", "--camera", s["camera"], "--board", s["board"], "--frames",
                  "2", "--out", o, s["frames"]], [o])]
    if kind == "board":
        return [([h4cal, "validate", "--robot", s["robot"], "--data", s["data"], "--result12",
                  s["result"], "--corners", s["corners"], "--board", s["board"], "--camera",
                  s["camera"]], []),
                ([h4cam, "make-board", "--board", s["board"], "--out", o + ".png"], [o + ".png"])]
    raise ValueError(kind)


def one_mutant(args):
    index, kind, text, seed, seeds, h4cal, h4cam, work, timeout = args
    rng = random.Random(seed * 100003 + index)
    d = os.path.join(work, f"m{index}")
    os.makedirs(d, exist_ok=True)
    ext = {"robot": ".yaml", "data": ".csv", "result": ".json", "camera": ".yaml",
           "board": ".yaml"}[kind]
    mutant = os.path.join(d, "mutant" + ext)
    with open(mutant, "wb") as f:
        f.write(mutate(text, rng))
    findings, counts = [], {"ok": 0, "refused": 0}
    for cmd, outs in commands(kind, mutant, seeds, h4cal, h4cam, d):
        verdict, detail = run(cmd, timeout, outs)
        if verdict in counts:
            counts[verdict] += 1
        else:
            keep = os.path.join(work, "findings", f"{kind}_{index}{ext}")
            os.makedirs(os.path.dirname(keep), exist_ok=True)
            shutil.copy(mutant, keep)
            findings.append(f"{verdict}: {' '.join(os.path.basename(c) for c in cmd[:2])} on "
                            f"{keep}: {detail}")
    shutil.rmtree(d, ignore_errors=True)
    return findings, counts


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--h4cal", required=True)
    ap.add_argument("--h4cam", required=True)
    ap.add_argument("--mutants", type=int, default=2000)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=10.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--work", default="")
    a = ap.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="h4_cli_mutants_")
    os.makedirs(work, exist_ok=True)
    seeds = make_seeds(os.path.abspath(a.h4cal), os.path.abspath(a.h4cam), work)
    kinds = ["robot", "data", "result", "camera", "board"]
    texts = {k: open(seeds[k], "rb").read() for k in kinds}
    tasks = [(i, kinds[i % len(kinds)], texts[kinds[i % len(kinds)]], a.seed, seeds,
              os.path.abspath(a.h4cal), os.path.abspath(a.h4cam), work, a.timeout)
             for i in range(a.mutants)]
    findings, totals, done = [], {"ok": 0, "refused": 0}, 0
    with concurrent.futures.ProcessPoolExecutor(a.jobs) as pool:
        for f, counts in pool.map(one_mutant, tasks, chunksize=4):
            findings += f
            for k in totals:
                totals[k] += counts[k]
            done += 1
            for line in f:
                print(line, flush=True)
            if done % 100 == 0:
                print(f"cli_mutants: {done}/{a.mutants} mutants, {len(findings)} findings",
                      file=sys.stderr, flush=True)
    runs = totals["ok"] + totals["refused"] + len(findings)
    print(f"cli_mutants: {a.mutants} mutants ({', '.join(kinds)}), {runs} runs: "
          f"{totals['ok']} accepted, {totals['refused']} refused, {len(findings)} findings "
          f"(work: {work})")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
