#!/usr/bin/env python3
"""PyTorch side of the LPT speed comparison (bench/compare.sh runs it next to bench/nn/lpt_bench).

An independently written PyTorch model with the release's structure (1x1 Conv2d + BatchNorm2d line
MLP, pre-norm encoder layers built on torch.nn.MultiheadAttention, Conv1d + BatchNorm1d heads, AdamW)
timed at the same shapes as lpt_bench. One workload per process so peak RSS is per workload.

    OPENBLAS_CORETYPE=SkylakeX OMP_NUM_THREADS=2 OPENBLAS_NUM_THREADS=2 \
        /usr/bin/python3 bench/torch_lpt.py junction_train [--iters 3] [--threads 2]
"""
import argparse
import resource
import statistics
import time

import torch
import torch.nn as nn
import torch.nn.functional as F


class PreNormLayer(nn.Module):
    def __init__(self, dim=256, heads=8, ffn=256, dropout=0.5):
        super().__init__()
        self.attn = nn.MultiheadAttention(dim, heads, dropout=dropout)  # sequence-first, as the release
        self.ln1, self.ln2 = nn.LayerNorm(dim), nn.LayerNorm(dim)
        self.fc1, self.fc2 = nn.Linear(dim, ffn), nn.Linear(ffn, dim)
        self.drop = nn.Dropout(dropout)

    def forward(self, x, mask):  # x (L, B, E)
        y = self.ln1(x)
        x = x + self.drop(self.attn(y, y, y, key_padding_mask=mask)[0])
        return x + self.drop(self.fc2(self.drop(F.relu(self.fc1(self.ln2(x))))))


class Encoder(nn.Module):
    def __init__(self):
        super().__init__()
        self.layer, self.norm = PreNormLayer(), nn.LayerNorm(256)

    def forward(self, x, mask=None):
        return self.norm(self.layer(x, mask))


def head(out):
    layers, widths = [], [256, 128, 64, 32]
    for a, b in zip(widths, widths[1:]):
        layers += [nn.Conv1d(a, b, 1), nn.BatchNorm1d(b), nn.ReLU(), nn.Dropout(0.1)]
    return nn.Sequential(*layers, nn.Conv1d(32, out, 1))


class Net(nn.Module):
    def __init__(self, in_dim, outs):
        super().__init__()
        widths, layers = [in_dim, 64, 64, 128, 128, 256], []
        for a, b in zip(widths, widths[1:]):
            layers += [nn.Conv2d(a, b, 1), nn.BatchNorm2d(b), nn.ReLU()]
        self.mlp = nn.Sequential(*layers)
        self.enc1, self.enc2 = Encoder(), Encoder()
        self.heads = nn.ModuleList(head(k) for k in outs)

    def forward(self, x, mask):  # x (B, G, N, F), mask (B, G, N)
        B, G, N, _ = x.shape
        h = self.mlp(x.permute(0, 3, 1, 2))  # (B, 256, G, N)
        h = h.permute(3, 0, 2, 1).reshape(N, B * G, 256)
        h = self.enc1(h, mask.reshape(B * G, N)).mean(dim=0)  # (B*G, 256)
        h = self.enc2(h.reshape(B, G, 256).transpose(0, 1))  # (G, B, 256)
        f = h.permute(1, 2, 0)  # (B, 256, G)
        return [hd(f) for hd in self.heads]


def batch(B, G, N, F_, classes):
    x = torch.rand(B, G, N, F_) - 0.5
    mask = torch.rand(B, G, N) < 0.4
    mask[..., 0] = False
    return x, mask, torch.randint(0, classes, (B, G)), 0.1 * torch.randn(B, 3, G)


WORKLOADS = {  # name: (B, G, N, F, train)
    "junction_train": (16, 256, 32, 7, True),
    "edge_train": (4, 512, 64, 6, True),
    "junction_infer": (1, 256, 32, 7, False),
    "edge_infer": (1, 435, 64, 6, False),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("workload", choices=sorted(WORKLOADS))
    ap.add_argument("--iters", type=int, default=None, help="timed iterations (default 3 train, 10 inference)")
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    torch.set_num_threads(args.threads)
    torch.manual_seed(1555)
    B, G, N, F_, train = WORKLOADS[args.workload]
    junction = args.workload.startswith("junction")
    net = Net(F_, [2, 3] if junction else [5])
    x, mask, labels, offsets = batch(B, G, N, F_, 2 if junction else 5)
    opt = torch.optim.AdamW(net.parameters(), lr=1e-3, weight_decay=1e-5)
    weight = torch.tensor([1.0, 3.0, 1.0, 1.0, 1.0])

    def step():
        if train:
            opt.zero_grad()
            outs = net(x, mask)
            if junction:
                cls = labels.float()
                l1 = ((outs[1] - offsets).abs().sum(1) * cls).sum(1) / (cls.sum(1) + 1e-8)
                loss = F.cross_entropy(outs[0], labels) + 10 * l1.mean()
            else:
                loss = F.cross_entropy(outs[0], labels, weight=weight)
            loss.backward()
            opt.step()
        else:
            with torch.no_grad():
                net(x, mask)

    net.train(train)
    step()  # warm-up
    times = []
    for _ in range(args.iters or (3 if train else 10)):
        t0 = time.perf_counter()
        step()
        times.append(time.perf_counter() - t0)
    rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"{args.workload} median_s={statistics.median(times):.4f} peak_rss_MB={rss_mb:.0f}")


if __name__ == "__main__":
    main()
