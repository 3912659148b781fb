#!/usr/bin/env python3
"""Temporal stability of exported RAE weights on `fovrt dataset` sequences, in PyTorch.

For each sequence (whole frames, zero-padded to multiples of 2^L like fovrt), runs the network
with its hidden state carried over the whole sequence and with the state reset before every frame,
and reports per frame, in linear demodulated illumination (the network's output^(1/γ)):
  temporal  mean |lum_t - lum_{t-1}|              (SVGF §5.4, what rae_temporal_probe measures)
  tdiff     mean |(out_t - out_{t-1}) - (tgt_t - tgt_{t-1})|  (luminance; the flicker the target lacks)
  l1        mean |lum_out - lum_tgt|
Frame 0 has no predecessor and frame 1 still carries the reset of frame 0: summaries are over
frames 2..T-1.

  python3 training/temporal_eval.py WEIGHTS.raew DATASET [--seq NAME ...] [--frames N] [--per-frame]
"""
import argparse
import json
import os
import sys

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rae_net  # noqa: E402


def lum(c):
    return 0.2126 * c[:, 0] + 0.7152 * c[:, 1] + 0.0722 * c[:, 2]


def run(net, x, reset, gamma_space=False):
    """x [T, C, H, W] network inputs -> [T, 3, H, W] output (linear, or as the network's γ space)."""
    hidden = None
    outs = []
    with torch.no_grad():
        for t in range(x.shape[0]):
            if reset:
                hidden = None
            y, hidden = net.forward_frame(x[t:t + 1], hidden)
            outs.append(y[0])
    y = torch.stack(outs)
    return y if gamma_space else rae_net.linear_output(y)


def series(out, tgt):
    lo, lt = lum(out), lum(tgt)
    T = out.shape[0]
    temporal = [0.0] + [(lo[t] - lo[t - 1]).abs().mean().item() for t in range(1, T)]
    tdiff = [0.0] + [((lo[t] - lo[t - 1]) - (lt[t] - lt[t - 1])).abs().mean().item() for t in range(1, T)]
    l1 = [(lo[t] - lt[t]).abs().mean().item() for t in range(T)]
    return temporal, tdiff, l1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("weights")
    ap.add_argument("data")
    ap.add_argument("--seq", nargs="*", help="sequence names (default: every uniform sequence, left eye)")
    ap.add_argument("--frames", type=int, default=0, help="first N frames (0 = all)")
    ap.add_argument("--per-frame", action="store_true")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--gamma-space", action="store_true",
                    help="measure output^γ against target^γ (the space of the training loss), not linear")
    args = ap.parse_args(argv)
    torch.set_num_threads(args.threads)
    net, _ = rae_net.load_weights(args.weights)
    net.eval()
    with open(os.path.join(args.data, "manifest.json")) as f:
        manifest = json.load(f)
    seqs = [s for s in manifest["sequences"]
            if (s["name"] in args.seq if args.seq else (s["mode"] == "uniform" and s["eye"] == 0))]
    m = 2 ** net.levels
    for s in seqs:
        inp = np.load(os.path.join(args.data, s["input"]), mmap_mode="r")
        tgt = np.load(os.path.join(args.data, s["target"]), mmap_mode="r")
        T = args.frames or inp.shape[0]
        H, W = inp.shape[2:]
        x = rae_net.gamma_inputs(torch.from_numpy(np.array(inp[:T, :net.in_channels])))
        x = rae_net.pad_to_multiple(x, m)
        y = torch.clamp(torch.from_numpy(np.array(tgt[:T])), min=0.0)
        if args.gamma_space:
            y = y ** rae_net.GAMMA
        res = {}
        for reset in (False, True):
            out = run(net, x, reset, args.gamma_space)[:, :, :H, :W]
            res[reset] = series(out, y)
        if args.per_frame:
            for t in range(1, T):
                print(f"  {s['name']} frame {t:2d}  temporal state {res[False][0][t]:.5f} reset {res[True][0][t]:.5f}"
                      f"  tdiff state {res[False][1][t]:.5f} reset {res[True][1][t]:.5f}"
                      f"  l1 state {res[False][2][t]:.5f} reset {res[True][2][t]:.5f}")
        mean = lambda v: float(np.mean(v[2:]))  # noqa: E731
        tt = float(np.mean(series(y, y)[0][2:]))
        print(f"{s['name']:28s} [{s['split']}] temporal state {mean(res[False][0]):.5f} reset {mean(res[True][0]):.5f}"
              f" (target {tt:.5f}) ratio {mean(res[False][0]) / mean(res[True][0]):.3f} |"
              f" tdiff {mean(res[False][1]):.5f} / {mean(res[True][1]):.5f} |"
              f" l1 {mean(res[False][2]):.5f} / {mean(res[True][2]):.5f}", flush=True)


if __name__ == "__main__":
    main()
