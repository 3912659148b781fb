"""The recurrent denoising autoencoder (Chaitanya et al. 2017) and its weight file.

Network (per frame, hidden state carried between frames):
  encoder level l = 0..L-1 (width w_l, resolution 1/2^l):
      x  = C(x)                       feed-forward conv
      h_l = R_l(x, h_l_prev)          recurrent block, also the skip connection
      x  = maxpool2x2(h_l)
  bottleneck (1/2^L, width w_{L-1}): x = C(x); h_L = R_L(x, h_L_prev)
  decoder level l = L-1..0:
      x = upsample2x2_nearest(x); x = cat([x, h_l]); x = C(x); x = C(x)     (width w_l)
  output: conv 3x3 to 3 channels, linear.
  C = conv 3x3 (zero padding 1) + leaky ReLU 0.1.
  R(I, h) = C(C(cat([C(I), h])))      (paper eq. 2: h_i = C(C(C(I_i) ∪ h_{i-1})))
With widths (32, 43, 57, 76, 101) and 7 inputs: 2.03M parameters (widths as in the paper's
§5.1, 32 then ×4/3 per level; its §5.2 counts 3.2M for its own network); quarter widths
(8, 11, 14, 19, 25): 127k. Frame sizes must be multiples of 2^L (pad_to_multiple).

Inputs (channel order), all produced by fovrt (denoise/reference/rae_features.*):
  0-2 noisy illumination demodulated by albedo (direct + indirect), linear; the network sees
      max(c, 0)^gamma (gamma = 0.2, paper §4.4), applied here after augmentation
  3-4 view-space normal x, y        5 depth d/(d+1) (d metres; background 1)
  6   roughness                     7 (optional) log2(max(n, 1))/4, n the sample count: the foveated
      spp extension (a pixel without a path sample is filled from its
      sampled neighbours and reads the mean of their value)
Output: illumination^gamma; fovrt inverts (max(y,0)^(1/gamma)) and remodulates.

Weight file (.raew, little endian), read by denoise/reference/rae_weights.cpp:
  char[4] "RAEW"; u32 version = 1; u32 levels L; u32 in_channels (7 or 8);
  u32 flags (bit 0: channel 7 is the sample-count channel); f32 gamma; u32 widths[L];
  u32 conv_count; then conv_count records in the fixed order of conv_layers():
      u32 out, u32 in, f32 weight[out][in][3][3] (PyTorch layout), f32 bias[out]
"""
import struct

import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F

PAPER_WIDTHS = (32, 43, 57, 76, 101)
QUARTER_WIDTHS = (8, 11, 14, 19, 25)
GAMMA = 0.2
MAGIC = b"RAEW"
VERSION = 1
FLAG_SAMPLE_COUNT = 1


class Conv(nn.Module):
    """3x3 conv, zero padding 1, optional leaky ReLU 0.1; He initialisation (paper §5.3)."""

    def __init__(self, cin, cout, act=True):
        super().__init__()
        self.conv = nn.Conv2d(cin, cout, 3, padding=1)
        nn.init.kaiming_normal_(self.conv.weight, a=0.1, nonlinearity="leaky_relu")
        nn.init.zeros_(self.conv.bias)
        self.act = act

    def forward(self, x):
        y = self.conv(x)
        return F.leaky_relu(y, 0.1) if self.act else y


class Recurrent(nn.Module):
    """h_i = C(C(cat(C(I_i), h_{i-1}))); h_{-1} = 0."""

    def __init__(self, width):
        super().__init__()
        self.c_in = Conv(width, width)
        self.c_h1 = Conv(2 * width, width)
        self.c_h2 = Conv(width, width)

    def forward(self, x, h):
        a = self.c_in(x)
        if h is None:
            h = torch.zeros_like(a)
        return self.c_h2(self.c_h1(torch.cat([a, h], 1)))


class RaeNet(nn.Module):
    def __init__(self, widths=QUARTER_WIDTHS, sample_count=False):
        super().__init__()
        self.widths = tuple(int(w) for w in widths)
        self.sample_count = bool(sample_count)
        self.in_channels = 8 if sample_count else 7
        L = len(self.widths)
        self.enc = nn.ModuleList()
        self.rec = nn.ModuleList()
        c = self.in_channels
        for w in self.widths:
            self.enc.append(Conv(c, w))
            self.rec.append(Recurrent(w))
            c = w
        self.bott = Conv(c, c)
        self.bott_rec = Recurrent(c)
        self.dec1 = nn.ModuleList()
        self.dec2 = nn.ModuleList()
        for l in reversed(range(L)):
            self.dec1.append(Conv(c + self.widths[l], self.widths[l]))
            self.dec2.append(Conv(self.widths[l], self.widths[l]))
            c = self.widths[l]
        self.out = Conv(c, 3, act=False)

    @property
    def levels(self):
        return len(self.widths)

    def conv_layers(self):
        """Every conv in the weight file's fixed order."""
        layers = []
        for e, r in zip(self.enc, self.rec):
            layers += [e, r.c_in, r.c_h1, r.c_h2]
        layers += [self.bott, self.bott_rec.c_in, self.bott_rec.c_h1, self.bott_rec.c_h2]
        for d1, d2 in zip(self.dec1, self.dec2):
            layers += [d1, d2]
        layers.append(self.out)
        return [m.conv for m in layers]

    def forward_frame(self, x, hidden):
        """One frame: x [B, C, H, W] (H, W multiples of 2^L); hidden: list of L+1 tensors or None."""
        L = self.levels
        if hidden is None:
            hidden = [None] * (L + 1)
        new_hidden = []
        skips = []
        for l in range(L):
            x = self.enc[l](x)
            h = self.rec[l](x, hidden[l])
            new_hidden.append(h)
            skips.append(h)
            x = F.max_pool2d(h, 2)
        x = self.bott(x)
        x = self.bott_rec(x, hidden[L])
        new_hidden.append(x)
        for i, l in enumerate(reversed(range(L))):
            x = F.interpolate(x, scale_factor=2, mode="nearest")
            x = torch.cat([x, skips[l]], 1)
            x = self.dec2[i](self.dec1[i](x))
        return self.out(x), new_hidden

    def forward(self, seq):
        """seq [B, T, C, H, W] -> [B, T, 3, H, W], hidden state reset at t = 0."""
        hidden = None
        outs = []
        for t in range(seq.shape[1]):
            y, hidden = self.forward_frame(seq[:, t], hidden)
            outs.append(y)
        return torch.stack(outs, 1)


def count_parameters(net):
    return sum(p.numel() for p in net.parameters())


def flops_per_pixel(net):
    """Multiply-adds x 2 of every conv per full-resolution pixel."""
    total = 0.0
    L = net.levels
    convs = net.conv_layers()
    scales = []
    for l in range(L):
        scales += [4.0 ** -l] * 4
    scales += [4.0 ** -L] * 4
    for l in reversed(range(L)):
        scales += [4.0 ** -l] * 2
    scales.append(1.0)
    for c, s in zip(convs, scales):
        total += 2 * 9 * c.in_channels * c.out_channels * s
    return total


def pad_to_multiple(x, m):
    """Zero-pads the last two dims at the bottom and right to multiples of m (what fovrt does)."""
    H, W = x.shape[-2:]
    ph, pw = (-H) % m, (-W) % m
    return F.pad(x, (0, pw, 0, ph)) if ph or pw else x


def gamma_inputs(x, gamma=GAMMA):
    """Raw features (colour linear) -> network inputs (colour^gamma). x [..., C, H, W]."""
    c = torch.clamp(x[..., 0:3, :, :], min=0.0) ** gamma
    return torch.cat([c, x[..., 3:, :, :]], -3)


def linear_output(y, gamma=GAMMA):
    """Network output (illumination^gamma) -> linear illumination, as fovrt's remodulation
    (RaeRemodulate: max(y, 0)^(1/gamma)) takes it."""
    return torch.clamp(y, min=0.0) ** (1.0 / gamma)


def save_weights(net, path, gamma=GAMMA):
    convs = net.conv_layers()
    with open(path, "wb") as f:
        f.write(MAGIC)
        f.write(struct.pack("<IIII", VERSION, net.levels, net.in_channels,
                            FLAG_SAMPLE_COUNT if net.sample_count else 0))
        f.write(struct.pack("<f", gamma))
        f.write(struct.pack("<%dI" % net.levels, *net.widths))
        f.write(struct.pack("<I", len(convs)))
        for c in convs:
            f.write(struct.pack("<II", c.out_channels, c.in_channels))
            f.write(c.weight.detach().cpu().numpy().astype("<f4").tobytes())
            f.write(c.bias.detach().cpu().numpy().astype("<f4").tobytes())


def load_weights(path):
    with open(path, "rb") as f:
        data = f.read()
    assert data[:4] == MAGIC, "not a .raew file"
    version, levels, cin, flags = struct.unpack_from("<IIII", data, 4)
    assert version == VERSION
    (gamma,) = struct.unpack_from("<f", data, 20)
    widths = struct.unpack_from("<%dI" % levels, data, 24)
    off = 24 + 4 * levels
    (count,) = struct.unpack_from("<I", data, off)
    off += 4
    net = RaeNet(widths, sample_count=bool(flags & FLAG_SAMPLE_COUNT))
    assert net.in_channels == cin
    convs = net.conv_layers()
    assert len(convs) == count
    with torch.no_grad():
        for c in convs:
            o, i = struct.unpack_from("<II", data, off)
            off += 8
            assert (o, i) == (c.out_channels, c.in_channels)
            n = o * i * 9
            c.weight.copy_(torch.from_numpy(np.frombuffer(data, "<f4", n, off).reshape(o, i, 3, 3).copy()))
            off += 4 * n
            c.bias.copy_(torch.from_numpy(np.frombuffer(data, "<f4", o, off).copy()))
            off += 4 * o
    assert off == len(data)
    return net, gamma
