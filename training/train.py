#!/usr/bin/env python3
"""Trains the recurrent denoising autoencoder (training/rae_net.py) on a `fovrt dataset` folder.

Paper recipe (Chaitanya et al. 2017, §4.3-4.4, §5.3): 7-frame sequences, 128² crops, batch 4;
loss 0.8 L1 + 0.1 HFEN (L1 of LoG σ 1.5) + 0.1 temporal (L1 of frame differences), per-frame
weights exp(-(6-t)²/8); augmentations: playback direction, camera stops, 90° rotations (view-space
normals rotated too), per-channel colour scale U[0, 2]; Adam 1e-3, β (0.9, 0.99), learning rate
ramped up tenfold geometrically, then ∝ 1/√t. CPU (torch.set_num_threads(--threads)) or a CUDA
GPU (--device cuda): the same recipe, the batches drawn on the CPU either way.

Writes into --out: train_log.csv (one row per --log-every steps), checkpoint.pt (every
--ckpt-every steps and at the end; --resume continues from it), rae.raew (the exported weights).

  python3 training/train.py --data DATASET --out training/runs/quarter --widths quarter --steps 4000
"""
import argparse
import csv
import json
import math
import os
import random
import sys
import time

import numpy as np
import torch
import torch.nn.functional as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rae_net  # noqa: E402

SEQ = 7
FRAME_WEIGHTS = torch.tensor([math.exp(-((6 - t) ** 2) / 8.0) for t in range(SEQ)])


def log_kernel(sigma=1.5, radius=4):
    r = torch.arange(-radius, radius + 1, dtype=torch.float32)
    y, x = torch.meshgrid(r, r, indexing="ij")
    q = (x * x + y * y) / (2 * sigma * sigma)
    k = -(1.0 - q) * torch.exp(-q) / (math.pi * sigma ** 4)
    return (k - k.mean()).view(1, 1, 2 * radius + 1, 2 * radius + 1)


LOG = log_kernel()


def hfen(x):
    """LoG of every channel, x [N, C, H, W]."""
    n, c, h, w = x.shape
    k = LOG.to(x.device)
    return F.conv2d(x.reshape(n * c, 1, h, w), k, padding=k.shape[-1] // 2).reshape(n, c, h, w)


def frame_weights(floor=0.0):
    """Per-frame loss weights: the paper's exp(-(6-t)²/8), raised to at least `floor`."""
    return torch.clamp(FRAME_WEIGHTS, min=floor)


def rae_loss(out, tgt, w_temporal=0.1, w_temporal_linear=0.0, fw=FRAME_WEIGHTS):
    """out, tgt [B, T, 3, H, W] in gamma space. Returns (total, l1, hfen, temporal, temporal_linear).

    Weights 0.8 / 0.1 / w_temporal (paper: 0.8 / 0.1 / 0.1) and, a deviation from the paper,
    w_temporal_linear on the same temporal L1 taken in linear space (out^(1/γ) against
    tgt^(1/γ)): γ = 0.2 compresses the flicker of bright regions that the temporal error of
    fovrt's experiments (mean |lum_t − lum_{t−1}|, linear) is made of."""
    B, T = out.shape[:2]
    w = fw[:T].to(out.device) / fw[:T].sum()
    l1 = ((out - tgt).abs().mean(dim=(0, 2, 3, 4)) * w).sum()
    hf = (hfen(out.flatten(0, 1)) - hfen(tgt.flatten(0, 1))).abs().view(B, T, -1).mean(dim=(0, 2))
    hf = (hf * w).sum()
    d_out = out[:, 1:] - out[:, :-1]
    d_tgt = tgt[:, 1:] - tgt[:, :-1]
    tw = w[1:] / w[1:].sum()
    tm = ((d_out - d_tgt).abs().mean(dim=(0, 2, 3, 4)) * tw).sum()
    if w_temporal_linear:
        lin_out = rae_net.linear_output(out)
        lin_tgt = rae_net.linear_output(tgt)
        dl_out = lin_out[:, 1:] - lin_out[:, :-1]
        dl_tgt = lin_tgt[:, 1:] - lin_tgt[:, :-1]
        tl = ((dl_out - dl_tgt).abs().mean(dim=(0, 2, 3, 4)) * tw).sum()
    else:
        tl = torch.zeros((), device=out.device)
    return 0.8 * l1 + 0.1 * hf + w_temporal * tm + w_temporal_linear * tl, l1, hf, tm, tl


def energy_loss(out, tgt, block=8, fw=FRAME_WEIGHTS):
    """A deviation from the paper: L1 in γ space between block means taken in linear light.

    out, tgt [B, T, 3, H, W] in γ space. Each is taken back to linear (x^(1/γ)), averaged over
    block × block pixels, and raised to γ again, so the term has the scale of the paper's L1 but
    compares energy: a network that keeps a region's texture while losing half its light pays it
    here, where the per-pixel L1 in γ space, which pulls towards the median, barely does."""
    B, T = out.shape[:2]
    w = fw[:T].to(out.device) / fw[:T].sum()
    m_out = F.avg_pool2d(rae_net.linear_output(out).flatten(0, 1), block)
    m_tgt = F.avg_pool2d(rae_net.linear_output(tgt).flatten(0, 1), block)
    # (m + 1e-6)^γ: the gradient of x^γ is unbounded at 0 (black blocks).
    d = ((m_out + 1e-6) ** rae_net.GAMMA - (m_tgt + 1e-6) ** rae_net.GAMMA).abs()
    return (d.view(B, T, -1).mean(dim=(0, 2)) * w).sum()


class Dataset:
    """Every sequence of one or more `fovrt dataset` folders, memory-mapped (see their manifest.json).
    Folders of one training run must agree on the channels and the γ."""

    def __init__(self, folders, split="train"):
        if isinstance(folders, str):
            folders = [folders]
        # inputs[i][r]: noise realisation r of sequence i (r = 0: "input"; r >= 1: "inputs_extra",
        # the same frames, camera and targets traced with other seeds: `fovrt dataset --noise-realisations`)
        self.inputs, self.targets, self.names = [], [], []
        self.manifest = None
        for folder in folders:
            with open(os.path.join(folder, "manifest.json")) as f:
                manifest = json.load(f)
            if self.manifest is None:
                self.manifest = manifest
            for key in ("channels", "gamma"):
                if manifest[key] != self.manifest[key]:
                    sys.exit(f"{folder}/manifest.json: {key} {manifest[key]} differs from {folders[0]}'s "
                             f"{self.manifest[key]}")
            for s in manifest["sequences"]:
                if s["split"] != split:
                    continue
                files = [s["input"]] + list(s.get("inputs_extra", []))
                self.inputs.append([np.load(os.path.join(folder, f), mmap_mode="r") for f in files])
                self.targets.append(np.load(os.path.join(folder, s["target"]), mmap_mode="r"))
                self.names.append(s["name"])

    def realisations(self):
        """Noise realisations every sequence has (1 = a dataset without extra noise)."""
        return min(len(r) for r in self.inputs) if self.inputs else 1

    def __len__(self):
        return len(self.inputs)


STOP_PROB, STOP_HOLD = 0.25, (2, 4)  # camera stops: probability, copies of the held frame (--stops)


def frame_indices(n, rng, augment, realisations=1):
    """7 (frame, noise realisation) pairs into a sequence of n frames: playback direction and
    camera stops.

    A camera stop (paper §4.3) holds the camera and the target at one frame for 1-3 extra frames
    "while advancing the noisy image to a different random seed": each held copy takes the next
    noise realisation of that frame (round robin over the dataset's realisations, so a held frame
    never repeats its predecessor's noise when there are at least two). With one realisation the
    held frame repeats its noise exactly, which is not the paper's camera stop."""
    start = rng.randrange(0, n - SEQ + 1)
    idx = [(i, 0) for i in range(start, start + SEQ)]
    if augment and rng.random() < STOP_PROB:  # camera stop: one frame held for 1-3 extra frames
        j = rng.randrange(0, SEQ)
        held = [(idx[j][0], k % realisations) for k in range(rng.randint(*STOP_HOLD))]
        idx = (idx[:j] + held + idx[j + 1:])[:SEQ]
    if augment and rng.random() < 0.5:
        idx.reverse()
    return idx


def rotate_normals(x, k):
    """View-space normal (x right, y up) under k counter-clockwise image rotations of 90°."""
    nx, ny = x[:, 3].clone(), x[:, 4].clone()
    for _ in range(k % 4):
        nx, ny = -ny, nx
    x = x.clone()
    x[:, 3], x[:, 4] = nx, ny
    return x


def sample_batch(ds, batch, crop, channels, rng, augment=True):
    xs, ys = [], []
    realisations = ds.realisations()
    for _ in range(batch):
        i = rng.randrange(len(ds))
        inp, tgt = ds.inputs[i], ds.targets[i]
        T, _, H, W = inp[0].shape
        idx = frame_indices(T, rng, augment, realisations)
        y0, x0 = rng.randrange(0, H - crop + 1), rng.randrange(0, W - crop + 1)
        x = torch.from_numpy(np.stack([inp[r][f, :channels, y0:y0 + crop, x0:x0 + crop] for f, r in idx]))
        y = torch.from_numpy(np.stack([tgt[f, :, y0:y0 + crop, x0:x0 + crop] for f, _ in idx]))
        if augment:
            k = rng.randrange(4)
            if k:
                x = rotate_normals(torch.rot90(x, k, dims=(2, 3)), k)
                y = torch.rot90(y, k, dims=(2, 3))
            s = torch.tensor([rng.uniform(0.0, 2.0) for _ in range(3)]).view(1, 3, 1, 1)
            x = x.clone()
            x[:, 0:3] *= s
            y = y * s
        xs.append(rae_net.gamma_inputs(x))
        ys.append(torch.clamp(y, min=0.0) ** rae_net.GAMMA)
    return torch.stack(xs), torch.stack(ys)


def learning_rate(step, base, ramp):
    """Tenfold geometric ramp-up over `ramp` steps, then base·sqrt(ramp/step). A fine-tuning run
    (--init) evaluates it at step + --schedule-offset, continuing the schedule it started from."""
    if step < ramp:
        return base * 10.0 ** (step / ramp - 1.0)
    return base * math.sqrt(ramp / max(step, 1))


def parse_widths(text):
    if text == "paper":
        return rae_net.PAPER_WIDTHS
    if text == "quarter":
        return rae_net.QUARTER_WIDTHS
    return tuple(int(w) for w in text.split(","))


def training_device(name):
    """The torch device --device names; one line and a non-zero exit when this torch cannot use it."""
    try:
        device = torch.device(name)
    except RuntimeError as e:
        sys.exit(f"--device {name}: {e}")
    if device.type == "cuda" and not torch.cuda.is_available():
        sys.exit(f"--device {name}: torch {torch.__version__} sees no CUDA device (torch.cuda.is_available() is false)")
    if device.type == "cuda" and (device.index or 0) >= torch.cuda.device_count():
        sys.exit(f"--device {name}: torch sees {torch.cuda.device_count()} CUDA device(s)")
    if device.type not in ("cpu", "cuda"):
        sys.exit(f"--device {name}: not cpu or cuda")
    return device


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", required=True, nargs="+", help="one or more `fovrt dataset` folders")
    ap.add_argument("--out", required=True)
    ap.add_argument("--widths", default="quarter", help="paper | quarter | comma list")
    ap.add_argument("--sample-count", action="store_true", help="8th input: log2(spp)/4")
    ap.add_argument("--steps", type=int, default=4000)
    ap.add_argument("--batch", type=int, default=4)
    ap.add_argument("--crop", type=int, default=128)
    ap.add_argument("--lr", type=float, default=1e-3)
    ap.add_argument("--ramp", type=int, default=200, help="steps of the tenfold ramp-up")
    ap.add_argument("--threads", type=int, default=2, help="CPU threads (with --device cpu, the network's)")
    ap.add_argument("--device", default="cpu", help="cpu | cuda | cuda:N: where the network trains")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--log-every", type=int, default=20)
    ap.add_argument("--ckpt-every", type=int, default=200)
    ap.add_argument("--resume", action="store_true")
    ap.add_argument("--keep-exports", action="store_true", help="also keep rae-step<N>.raew of every checkpoint")
    ap.add_argument("--temporal-weight", type=float, default=0.1,
                    help="weight of the temporal L1 term (paper 0.1; spatial 0.8 and HFEN 0.1 stay)")
    ap.add_argument("--temporal-linear", type=float, default=0.0,
                    help="weight of the temporal L1 in linear space (0 = the paper's loss)")
    ap.add_argument("--energy-weight", type=float, default=0.0,
                    help="weight of the block-energy term (energy_loss; 0 = the paper's loss)")
    ap.add_argument("--frame-weight-floor", type=float, default=0.0,
                    help="per-frame loss weights max(exp(-(6-t)²/8), floor); 0 = the paper's")
    ap.add_argument("--stops", default="0.25,2,4",
                    help="camera stops: probability, fewest and most copies of the held frame")
    ap.add_argument("--init", help="start from these exported weights (.raew): fine-tuning, fresh Adam state")
    ap.add_argument("--schedule-offset", type=int, default=0,
                    help="learning rate of step s is the schedule's at s + offset (fine-tuning)")
    ap.add_argument("--fixed-batch", action="store_true",
                    help="one batch (no augmentation) for every step: the CI smoke test's overfit")
    args = ap.parse_args(argv)

    global STOP_PROB, STOP_HOLD
    p, lo, hi = args.stops.split(",")
    STOP_PROB, STOP_HOLD = float(p), (int(lo), int(hi))
    torch.set_num_threads(args.threads)
    device = training_device(args.device)
    torch.manual_seed(args.seed)
    rng = random.Random(args.seed)
    os.makedirs(args.out, exist_ok=True)
    train = Dataset(args.data, "train")
    val = Dataset(args.data, "eval")
    if len(train) == 0:
        sys.exit(f"no training sequences in {' '.join(args.data)}")
    net = rae_net.RaeNet(parse_widths(args.widths), sample_count=args.sample_count)
    if args.init:
        init, _ = rae_net.load_weights(args.init)
        if init.widths != net.widths or init.in_channels != net.in_channels:
            sys.exit(f"--init {args.init}: widths {init.widths} / {init.in_channels} inputs, "
                     f"this run {net.widths} / {net.in_channels}")
        net.load_state_dict(init.state_dict())
    channels = net.in_channels
    net.to(device)
    opt = torch.optim.Adam(net.parameters(), lr=args.lr, betas=(0.9, 0.99))
    step, elapsed = 0, 0.0
    ckpt_path = os.path.join(args.out, "checkpoint.pt")
    log_path = os.path.join(args.out, "train_log.csv")
    if args.resume and os.path.exists(ckpt_path):
        ck = torch.load(ckpt_path, map_location=device)
        net.load_state_dict(ck["net"])
        opt.load_state_dict(ck["opt"])
        step, elapsed = ck["step"], ck["elapsed"]
        rng.setstate(ck["rng"])
        torch.set_rng_state(ck["torch_rng"].cpu())  # map_location moved it to the device
        print(f"resumed at step {step}", flush=True)
    else:
        with open(log_path, "w", newline="") as f:
            csv.writer(f).writerow(["step", "seconds", "lr", "loss", "l1", "hfen", "temporal", "val_loss",
                                    "temporal_linear", "energy", "val_energy"])
    print(f"widths {net.widths} inputs {channels}: {rae_net.count_parameters(net)} parameters, "
          f"{rae_net.flops_per_pixel(net):.0f} FLOP/px; {len(train)} train / {len(val)} eval sequences, "
          f"{train.realisations()} noise realisation(s) each; temporal weight {args.temporal_weight}"
          f", linear {args.temporal_linear}; frame weights {[round(v, 3) for v in frame_weights(args.frame_weight_floor).tolist()]}"
          + (f"; from {args.init}" if args.init else ""), flush=True)
    # A fixed validation batch (held-out scenes, no augmentation) for the loss curve.
    vbatch = None
    src = val if len(val) else train
    if src is not None and len(src):
        vbatch = tuple(t.to(device) for t in
                       sample_batch(src, 4, args.crop, channels, random.Random(12345), augment=False))

    def save():
        torch.save({"net": net.state_dict(), "opt": opt.state_dict(), "step": step, "elapsed": elapsed,
                    "rng": rng.getstate(), "torch_rng": torch.get_rng_state(), "args": vars(args)},
                   ckpt_path + ".tmp")
        os.replace(ckpt_path + ".tmp", ckpt_path)
        rae_net.save_weights(net, os.path.join(args.out, "rae.raew"))
        if args.keep_exports:
            rae_net.save_weights(net, os.path.join(args.out, f"rae-step{step}.raew"))

    acc = np.zeros(6)
    n_acc = 0
    while step < args.steps:
        t0 = time.time()
        lr = learning_rate(step + args.schedule_offset, args.lr, args.ramp)
        for g in opt.param_groups:
            g["lr"] = lr
        if args.fixed_batch:
            if step == 0 or "fixed" not in locals():
                fixed = sample_batch(train, args.batch, args.crop, channels, random.Random(args.seed), augment=False)
            x, y = fixed
        else:
            x, y = sample_batch(train, args.batch, args.crop, channels, rng)
        x, y = x.to(device), y.to(device)
        out = net(x)
        loss, l1, hf, tm, tl = rae_loss(out, y, args.temporal_weight, args.temporal_linear,
                                        frame_weights(args.frame_weight_floor))
        if args.energy_weight:
            en = energy_loss(out, y, fw=frame_weights(args.frame_weight_floor))
            loss = loss + args.energy_weight * en
        else:
            en = torch.zeros((), device=device)
        opt.zero_grad()
        loss.backward()
        opt.step()
        step += 1
        elapsed += time.time() - t0
        acc += [loss.item(), l1.item(), hf.item(), tm.item(), tl.item(), en.item()]
        n_acc += 1
        if step % args.log_every == 0 or step == args.steps:
            vloss, venergy = float("nan"), float("nan")
            if vbatch is not None:
                with torch.no_grad():
                    vout = net(vbatch[0])
                    vloss = rae_loss(vout, vbatch[1])[0].item()  # paper weights: comparable
                    venergy = energy_loss(vout, vbatch[1]).item()
            m = acc / n_acc
            with open(log_path, "a", newline="") as f:
                csv.writer(f).writerow([step, f"{elapsed:.1f}", f"{lr:.3e}"] + [f"{v:.5f}" for v in m[:4]] +
                                       [f"{vloss:.5f}", f"{m[4]:.5f}", f"{m[5]:.5f}", f"{venergy:.5f}"])
            print(f"step {step} {elapsed:.0f}s lr {lr:.2e} loss {m[0]:.4f} (l1 {m[1]:.4f} hfen {m[2]:.4f} "
                  f"temporal {m[3]:.4f} linear {m[4]:.4f} energy {m[5]:.4f}) val {vloss:.4f} energy {venergy:.4f}",
                  flush=True)
            acc[:] = 0
            n_acc = 0
        if step % args.ckpt_every == 0:
            save()
    save()
    print(f"done: {step} steps in {elapsed:.0f} s; weights {os.path.join(args.out, 'rae.raew')}", flush=True)


if __name__ == "__main__":
    main()
