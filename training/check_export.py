#!/usr/bin/env python3
"""Writes the exported network's PyTorch outputs on a dataset sequence for tests/tools/rae_check.

  check_export.py WEIGHTS DATASET OUT_DIR [--frames 3] [--crop 64]
Reads the first sequence of DATASET's manifest, crops the top-left (crop x crop) of its first
frames, raises colour to γ, runs the loaded .raew network with the hidden state carried and saves
OUT_DIR/input.npy [T, C, H, W] and OUT_DIR/output.npy [T, 3, H, W].
"""
import argparse
import json
import os
import sys

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rae_net  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("weights")
    ap.add_argument("data")
    ap.add_argument("out")
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--crop", type=int, default=64)
    a = ap.parse_args()
    net, gamma = rae_net.load_weights(a.weights)
    with open(os.path.join(a.data, "manifest.json")) as f:
        seq = json.load(f)["sequences"][0]
    raw = np.load(os.path.join(a.data, seq["input"]))[: a.frames, : net.in_channels, : a.crop, : a.crop]
    x = rae_net.gamma_inputs(torch.from_numpy(np.ascontiguousarray(raw)), gamma)
    x = rae_net.pad_to_multiple(x, 2 ** net.levels)
    with torch.no_grad():
        y = net(x.unsqueeze(0))[0]
    os.makedirs(a.out, exist_ok=True)
    np.save(os.path.join(a.out, "input.npy"), x.numpy().astype("<f4"))
    np.save(os.path.join(a.out, "output.npy"), y.numpy().astype("<f4"))


if __name__ == "__main__":
    main()
