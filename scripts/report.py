#!/usr/bin/env python3
"""Plots of fibrenet campaigns, read from a results database (SQLite). Called by
`fibrenet report --db FILE --out DIR [--campaign NAME]`; runs on its own as well.

For each campaign it writes, under DIR:
  <campaign>_objective.png             objective against evaluation, best feasible so far
  <campaign>_softness_strength.png     softness-strength scatter: feasible region, Pareto front
  <campaign>_variables_vs_metrics.png  each design variable against each goal metric

The database is opened read-only, so this may run while a campaign writes the file.
Exit codes: 0 success, 1 failure, 2 bad input (missing file, not a fibrenet database, no such
campaign).
"""
import argparse
import json
import os
import re
import sqlite3
import sys

try:
    import tomllib  # Python >= 3.11
except ImportError:  # pragma: no cover
    tomllib = None

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

APPLICATION_ID = 0x46424E54  # "FBNT", db/schema.h


class BadInput(Exception):
    pass


def open_db(path):
    if not os.path.isfile(path):
        raise BadInput(f"--db {path}: no such file")
    try:
        con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
        app_id = con.execute("PRAGMA application_id").fetchone()[0]
    except sqlite3.DatabaseError as e:
        raise BadInput(f"--db {path}: not an SQLite database ({e})")
    if app_id != APPLICATION_ID:
        raise BadInput(f"--db {path}: not a fibrenet results database")
    return con


def read_goals(spec_text):
    """objective (kind, metric or targets), constraints {metric: (min, max)} from the stored
    campaign file; empty goals if it cannot be read."""
    goals = {"kind": None, "metric": None, "targets": {}, "constraints": {}}
    if tomllib is None:
        return goals
    try:
        spec = tomllib.loads(spec_text)
    except Exception:  # a campaign file this script cannot read: plot without goals
        return goals
    g = spec.get("goals", {})
    if "minimise" in g:
        goals["kind"], goals["metric"] = "minimise", g["minimise"]
    elif "maximise" in g:
        goals["kind"], goals["metric"] = "maximise", g["maximise"]
    elif "targets" in g:
        goals["kind"] = "targets"
        for name, t in g["targets"].items():
            goals["targets"][name] = t["value"] if isinstance(t, dict) else t
    for name, c in g.get("constraints", {}).items():
        goals["constraints"][name] = (c.get("min"), c.get("max"))
    goals["variables"] = [v.get("key") for v in spec.get("variables", [])]
    return goals


def goal_metrics(goals):
    names = []
    if goals["metric"]:
        names.append(goals["metric"])
    names += [n for n in goals["targets"] if n not in names]
    names += [n for n in goals["constraints"] if n not in names]
    return names


def read_candidates(con, campaign):
    rows = con.execute(
        "SELECT candidate_id, eval_index, status, fidelity, objective, feasible, parameters, "
        "metrics, reason FROM candidate_summary WHERE campaign = ? ORDER BY eval_index",
        (campaign,),
    ).fetchall()
    out = []
    for cid, index, status, fidelity, objective, feasible, params, metrics, reason in rows:
        out.append({
            "id": cid, "index": index, "status": status, "fidelity": fidelity,
            "objective": objective, "feasible": bool(feasible) if feasible is not None else None,
            "parameters": json.loads(params) if params else {},
            "metrics": json.loads(metrics) if metrics else {}, "reason": reason,
        })
    return out


def safe_name(name):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name)


def plot_objective(campaign, goals, cands, path):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    done = [c for c in cands if c["status"] == "done"]
    sign = -1.0 if goals["kind"] == "maximise" else 1.0  # show a maximised metric as itself
    fidelities = sorted({c["fidelity"] for c in done}, key=lambda f: min(
        c["index"] for c in done if c["fidelity"] == f))
    markers = "osD^v<>"
    for k, fid in enumerate(fidelities):
        for feasible in (True, False):
            pts = [c for c in done if c["fidelity"] == fid and c["feasible"] == feasible]
            if not pts:
                continue
            ax.scatter([c["index"] for c in pts], [sign * c["objective"] for c in pts],
                       marker=markers[k % len(markers)], s=28,
                       facecolors="tab:blue" if feasible else "none", edgecolors="tab:blue",
                       label=f"{fid}, {'feasible' if feasible else 'infeasible'}")
    # Best feasible so far (first fidelity level: the search).
    if fidelities:
        best, xs, ys = None, [], []
        for c in done:
            if c["fidelity"] != fidelities[0] or not c["feasible"]:
                continue
            if best is None or c["objective"] < best:
                best = c["objective"]
            xs.append(c["index"])
            ys.append(sign * best)
        if xs:
            ax.step(xs, ys, where="post", color="tab:green", label="best feasible so far")
    failed = [c for c in cands if c["status"] == "failed"]
    if failed:
        top = max([sign * c["objective"] for c in done] or [0.0])
        ax.scatter([c["index"] for c in failed], [top] * len(failed), marker="x",
                   color="tab:red", label="failed (penalty)")
    label = {"minimise": f"minimise {goals['metric']}", "maximise": f"maximise {goals['metric']}",
             "targets": "distance to targets"}.get(goals["kind"], "objective")
    ax.set_xlabel("evaluation")
    ax.set_ylabel(label)
    ax.set_title(f"{campaign}: objective against evaluation")
    ax.grid(alpha=0.3)
    if done or failed:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def pick_axes(goals, names, x_metric, y_metric):
    """The softness (x) and strength (y) metrics to plot."""
    preferred = goal_metrics(goals) + [n for n in names if n not in goal_metrics(goals)]
    if not x_metric:
        x_metric = next((n for n in preferred if "soft" in n.lower()), None)
    if not y_metric:
        y_metric = next((n for n in preferred if "strength" in n.lower() or "tensile" in n.lower()),
                        None)
    rest = [n for n in preferred if n not in (x_metric, y_metric)]
    x_metric = x_metric or (rest.pop(0) if rest else None)
    y_metric = y_metric or (rest.pop(0) if rest else None)
    return x_metric, y_metric


def larger_is_better(goals, metric):
    if goals["metric"] == metric:
        return goals["kind"] == "maximise"
    lo, hi = goals["constraints"].get(metric, (None, None))
    return not (hi is not None and lo is None)


def pareto(points, better_x, better_y):
    """Non-dominated points (x, y); 'better' says whether larger is better on each axis."""
    sx, sy = (1 if better_x else -1), (1 if better_y else -1)
    front = []
    for p in points:
        dominated = any(sx * q[0] >= sx * p[0] and sy * q[1] >= sy * p[1] and q != p
                        for q in points)
        if not dominated:
            front.append(p)
    return sorted(set(front))


def plot_tradeoff(campaign, goals, cands, path, x_metric, y_metric):
    done = [c for c in cands if c["status"] == "done"]
    names = sorted({n for c in done for n in c["metrics"]})
    xm, ym = pick_axes(goals, names, x_metric, y_metric)
    fig, ax = plt.subplots(figsize=(6.5, 5))
    if not xm or not ym:
        ax.text(0.5, 0.5, "fewer than two metrics to plot", ha="center", transform=ax.transAxes)
    else:
        pts = [c for c in done if xm in c["metrics"] and ym in c["metrics"]]
        for feasible, colour in ((True, "tab:blue"), (False, "tab:gray")):
            sel = [c for c in pts if c["feasible"] == feasible]
            ax.scatter([c["metrics"][xm] for c in sel], [c["metrics"][ym] for c in sel], s=22,
                       color=colour, alpha=0.8,
                       label="feasible" if feasible else "infeasible")
        xs = [c["metrics"][xm] for c in pts]
        ys = [c["metrics"][ym] for c in pts]
        if xs:
            pad_x = 0.05 * ((max(xs) - min(xs)) or 1.0)
            pad_y = 0.05 * ((max(ys) - min(ys)) or 1.0)
            x0, x1 = min(xs) - pad_x, max(xs) + pad_x
            y0, y1 = min(ys) - pad_y, max(ys) + pad_y
            cx = goals["constraints"].get(xm, (None, None))
            cy = goals["constraints"].get(ym, (None, None))
            if any(v is not None for v in cx + cy):
                fx0 = cx[0] if cx[0] is not None else x0
                fx1 = cx[1] if cx[1] is not None else x1
                fy0 = cy[0] if cy[0] is not None else y0
                fy1 = cy[1] if cy[1] is not None else y1
                x0, x1 = min(x0, fx0), max(x1, fx1)
                y0, y1 = min(y0, fy0), max(y1, fy1)
                ax.fill_between([fx0, fx1], fy0, fy1, color="tab:green", alpha=0.12,
                                label="feasible region (these two goals)")
            front = pareto(list(zip(xs, ys)), larger_is_better(goals, xm),
                           larger_is_better(goals, ym))
            if front:
                fx, fy = zip(*sorted(front, key=lambda p: p[0]))
                ax.plot(fx, fy, "-o", color="tab:orange", ms=4, label="Pareto front")
            for name, value in goals["targets"].items():
                if name == xm:
                    ax.axvline(value, color="tab:red", ls="--", lw=1, label=f"target {name}")
                if name == ym:
                    ax.axhline(value, color="tab:red", ls=":", lw=1, label=f"target {name}")
            ax.set_xlim(x0, x1)
            ax.set_ylim(y0, y1)
            ax.legend(fontsize=8)
        ax.set_xlabel(xm)
        ax.set_ylabel(ym)
    ax.set_title(f"{campaign}: softness against strength")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_variables(campaign, goals, cands, path):
    done = [c for c in cands if c["status"] == "done"]
    variables = goals.get("variables") or sorted({k for c in cands for k in c["parameters"]})
    metrics = goal_metrics(goals) or sorted({n for c in done for n in c["metrics"]})[:4]
    metrics = [m for m in metrics if any(m in c["metrics"] for c in done)] or metrics[:1]
    rows, cols = max(1, len(metrics)), max(1, len(variables))
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols + 0.6, 2.6 * rows + 0.6),
                             squeeze=False)
    for i, m in enumerate(metrics):
        for j, v in enumerate(variables):
            ax = axes[i][j]
            sel = [c for c in done if m in c["metrics"] and v in c["parameters"]]
            ax.scatter([c["parameters"][v] for c in sel], [c["metrics"][m] for c in sel], s=12,
                       c=["tab:blue" if c["feasible"] else "tab:gray" for c in sel])
            lo, hi = goals["constraints"].get(m, (None, None))
            for bound in (lo, hi):
                if bound is not None:
                    ax.axhline(bound, color="tab:green", ls="--", lw=1)
            if m in goals["targets"]:
                ax.axhline(goals["targets"][m], color="tab:red", ls=":", lw=1)
            if i == rows - 1:
                ax.set_xlabel(v)
            if j == 0:
                ax.set_ylabel(m)
            ax.grid(alpha=0.3)
    fig.suptitle(f"{campaign}: design variables against goal metrics")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--db", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--campaign")
    parser.add_argument("--x-metric", help="softness metric of the scatter (default: guessed)")
    parser.add_argument("--y-metric", help="strength metric of the scatter (default: guessed)")
    parser.add_argument("--json", action="store_true", help="print written files as JSON")
    args = parser.parse_args(argv)
    try:
        con = open_db(args.db)
        query = "SELECT name, spec_text FROM campaigns"
        params = ()
        if args.campaign:
            query += " WHERE name = ?"
            params = (args.campaign,)
        campaigns = con.execute(query + " ORDER BY id", params).fetchall()
        if args.campaign and not campaigns:
            raise BadInput(f"--campaign '{args.campaign}': no such campaign in {args.db}")
        os.makedirs(args.out, exist_ok=True)
        written = []
        for name, spec_text in campaigns:
            goals = read_goals(spec_text)
            goals.setdefault("variables", [])
            cands = read_candidates(con, name)
            base = os.path.join(args.out, safe_name(name))
            plot_objective(name, goals, cands, base + "_objective.png")
            plot_tradeoff(name, goals, cands, base + "_softness_strength.png", args.x_metric,
                          args.y_metric)
            plot_variables(name, goals, cands, base + "_variables_vs_metrics.png")
            written += [base + s for s in ("_objective.png", "_softness_strength.png",
                                           "_variables_vs_metrics.png")]
    except BadInput as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps({"files": written}, indent=2))
    else:
        for f in written:
            print(f)
        if not written:
            print("no campaigns in the database", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
