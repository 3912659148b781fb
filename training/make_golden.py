#!/usr/bin/env python3
"""Golden files for tests/denoise_rae_test.cpp: a small seeded network (3 levels, widths 4, 6, 8,
8 inputs with the sample-count flag) exported as .raew, two frames of random inputs (colour
already raised to γ) and PyTorch's outputs with the hidden state carried from frame 0 to frame 1.

  /usr/bin/python3 training/make_golden.py tests/data/rae
"""
import os
import sys

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rae_net  # noqa: E402


def main(out):
    os.makedirs(out, exist_ok=True)
    torch.manual_seed(20240601)
    net = rae_net.RaeNet((4, 6, 8), sample_count=True)
    with torch.no_grad():  # non-zero biases, so bias handling is tested too
        for c in net.conv_layers():
            c.bias.uniform_(-0.1, 0.1)
    rae_net.save_weights(net, os.path.join(out, "golden.raew"))
    T, H, W = 2, 24, 40
    raw = torch.rand(1, T, 8, H, W)
    raw[:, :, 0:3] *= 4.0           # HDR colour
    raw[:, :, 3:5] = raw[:, :, 3:5] * 2 - 1  # normal x, y
    x = rae_net.gamma_inputs(raw)
    with torch.no_grad():
        y = net(x)
    np.save(os.path.join(out, "golden_input.npy"), x[0].numpy().astype("<f4"))
    np.save(os.path.join(out, "golden_output.npy"), y[0].numpy().astype("<f4"))
    # The loader round trip: the file read back gives the same outputs.
    net2, _ = rae_net.load_weights(os.path.join(out, "golden.raew"))
    with torch.no_grad():
        assert torch.equal(net2(x), y)
    print(f"golden: {rae_net.count_parameters(net)} parameters, output range "
          f"[{y.min().item():.3f}, {y.max().item():.3f}] -> {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tests/data/rae")
