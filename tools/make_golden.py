#!/usr/bin/env python3
"""Regenerates the PyTorch reference fixtures of tests/nn (tests/data/nn/*.safetensors).

An independent PyTorch implementation of the release's networks (1x1 Conv2d + BatchNorm2d line MLP,
pre-norm Transformer encoders, Conv1d + BatchNorm1d heads) is run in float64 on float32 weights and
inputs; outputs, losses, every parameter gradient and optimiser trajectories are stored so the C++
engine can be checked against it. Needs Debian's python3-torch and numpy (run with /usr/bin/python3);
only needed to regenerate the fixtures, never by the test suite.

    /usr/bin/python3 tools/make_golden.py [--out tests/data/nn]
"""
import argparse
import json
import math
import os
import struct
import sys

import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F

MASK64 = (1 << 64) - 1


# ------------------------------------------------------------------------------------------ file format
def write_safetensors(path, tensors, metadata=None):
    """Minimal safetensors writer (the `safetensors` package is not packaged by Debian)."""
    codes = {np.dtype(np.float32): "F32", np.dtype(np.float64): "F64", np.dtype(np.int64): "I64",
             np.dtype(np.bool_): "BOOL"}
    header, blobs, offset = {}, [], 0
    for name, value in tensors.items():
        arr = np.asarray(value)
        if not arr.flags.c_contiguous:  # (np.ascontiguousarray would turn scalars into shape [1])
            arr = arr.copy(order="C")
        if arr.dtype not in codes:
            raise ValueError(f"{name}: unsupported dtype {arr.dtype}")
        data = arr.astype(arr.dtype.newbyteorder("<")).tobytes()
        header[name] = {"dtype": codes[arr.dtype], "shape": list(arr.shape),
                        "data_offsets": [offset, offset + len(data)]}
        blobs.append(data)
        offset += len(data)
    if metadata:
        header["__metadata__"] = {k: str(v) for k, v in metadata.items()}
    text = json.dumps(header, separators=(",", ":")).encode()
    text += b" " * ((8 - len(text) % 8) % 8)
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(struct.pack("<Q", len(text)))
        f.write(text)
        for blob in blobs:
            f.write(blob)
    os.replace(tmp, path)


# ------------------------------------------------------------------ the engine's counter-based generator
def rng_uniform_f(seed, count):
    """Rng(seed).uniform_f(i) for i in [0, count), bit-exact with core/rng.h (splitmix64 finaliser)."""
    with np.errstate(over="ignore"):
        def mix(z):
            z = z + np.uint64(0x9E3779B97F4A7C15)
            z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
            z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
            return z ^ (z >> np.uint64(31))
        n = np.arange(count, dtype=np.uint64)
        base = np.uint64(seed) * np.uint64(0x9E3779B97F4A7C15)
        bits = mix(base + mix(n))
        return (bits >> np.uint64(40)).astype(np.float64) * 2.0 ** -24


def fnv1a64(text):
    h = 0xCBF29CE484222325
    for byte in text.encode():
        h = ((h ^ byte) * 0x100000001B3) & MASK64
    return h


def hashed_value(name, shape):
    """Deterministic test weights, reproduced by tests/nn/golden_util.cpp: U(lo, hi) from Rng(fnv1a64(name))."""
    if name.endswith("running_var"):
        lo, hi = 0.5, 1.5
    elif name.endswith("running_mean"):
        lo, hi = -0.2, 0.2
    elif len(shape) == 2:
        bound = 1.0 / math.sqrt(shape[1])
        lo, hi = -bound, bound
    elif name.endswith("bias"):
        lo, hi = -0.1, 0.1
    else:
        lo, hi = 0.5, 1.5
    count = int(np.prod(shape)) if shape else 1
    u = rng_uniform_f(fnv1a64(name), count)
    return (lo + (hi - lo) * u).astype(np.float32).reshape(shape)


# ---------------------------------------------------------------------------- the reference networks
class Attention(nn.Module):
    """Packed-projection multi-head self-attention. A query whose keys are all padded gets zero output
    (torch.nn.MultiheadAttention would produce NaN there); otherwise identical to it (checked below)."""

    def __init__(self, dim, heads, attn_dropout):
        super().__init__()
        self.heads, self.p = heads, attn_dropout
        self.in_proj_weight = nn.Parameter(torch.empty(3 * dim, dim))
        self.in_proj_bias = nn.Parameter(torch.zeros(3 * dim))
        self.out_proj = nn.Linear(dim, dim)
        nn.init.xavier_uniform_(self.in_proj_weight)
        nn.init.zeros_(self.out_proj.bias)

    def forward(self, x, key_padding_mask):  # x (B, L, E), mask (B, L) True = padded
        B, L, E = x.shape
        H, D = self.heads, E // self.heads
        q, k, v = F.linear(x, self.in_proj_weight, self.in_proj_bias).chunk(3, dim=-1)
        q, k, v = (t.reshape(B, L, H, D).transpose(1, 2) for t in (q, k, v))
        scores = q @ k.transpose(-1, -2) / math.sqrt(D)
        if key_padding_mask is not None:
            empty = key_padding_mask.all(dim=-1)
            masked = key_padding_mask & ~empty[:, None]
            scores = scores.masked_fill(masked[:, None, None, :], float("-inf"))
        weights = scores.softmax(dim=-1)
        if key_padding_mask is not None:
            weights = weights * (~empty).to(weights.dtype)[:, None, None, None]
        weights = F.dropout(weights, self.p, self.training)
        out = (weights @ v).transpose(1, 2).reshape(B, L, E)
        return self.out_proj(out)


class EncoderLayer(nn.Module):
    def __init__(self, dim, heads, ffn, dropout, attn_dropout):
        super().__init__()
        self.self_attn = Attention(dim, heads, attn_dropout)
        self.linear1, self.linear2 = nn.Linear(dim, ffn), nn.Linear(ffn, dim)
        self.norm1, self.norm2 = nn.LayerNorm(dim), nn.LayerNorm(dim)
        self.dropout, self.dropout1, self.dropout2 = nn.Dropout(dropout), nn.Dropout(dropout), nn.Dropout(dropout)

    def forward(self, x, mask):
        x = x + self.dropout1(self.self_attn(self.norm1(x), mask))
        return x + self.dropout2(self.linear2(self.dropout(F.relu(self.linear1(self.norm2(x))))))


class Encoder(nn.Module):
    def __init__(self, c, layers):
        super().__init__()
        self.layers = nn.ModuleList(
            EncoderLayer(c["hidden_dim"], c["num_heads"], c["ffn_dim"], c["dropout"], c["attn_dropout"])
            for _ in range(layers))
        self.norm = nn.LayerNorm(c["hidden_dim"])
        for p in self.parameters():  # the release re-initialises every matrix of its transformers
            if p.dim() > 1:
                nn.init.xavier_uniform_(p)

    def forward(self, x, mask):
        for layer in self.layers:
            x = layer(x, mask)
        return self.norm(x)


class ConvBn(nn.Module):
    def __init__(self, conv, bn):
        super().__init__()
        self.fc, self.bn = conv, bn


class LPT(nn.Module):
    def __init__(self, c):
        super().__init__()
        self.c = c
        dims = [c["input_dim"]] + c["mlp_dims"]
        self.mlp = nn.ModuleList(ConvBn(nn.Conv2d(a, b, 1), nn.BatchNorm2d(b)) for a, b in zip(dims, dims[1:]))
        self.enc1 = Encoder(c, c["line_layers"])
        self.enc2 = Encoder(c, c["patch_layers"])

    def forward(self, x, mask):  # x (B, G, N, F), mask (B, G, N)
        B, G, N, _ = x.shape
        h = x.permute(0, 3, 1, 2)  # channels first, as the release
        for block in self.mlp:
            h = F.relu(block.bn(block.fc(h)))
        h = h.permute(0, 2, 3, 1).reshape(B * G, N, -1)
        m = mask.reshape(B * G, N)
        h = self.enc1(h, m)
        if self.c["pool"] == "mean_all":
            h = h.mean(dim=1)
        else:
            valid = (~m).to(h.dtype)
            h = (h * valid[..., None]).sum(dim=1) / valid.sum(dim=1, keepdim=True).clamp(min=1.0)
        return self.enc2(h.reshape(B, G, -1), None)


class Head(nn.Module):
    def __init__(self, dim, c, out):
        super().__init__()
        widths = [dim] + c["dims"]
        for i, (a, b) in enumerate(zip(widths, widths[1:])):
            self.add_module(str(i), ConvBn(nn.Conv1d(a, b, 1), nn.BatchNorm1d(b)))
        self.n = len(c["dims"])
        self.drop = nn.Dropout(c["dropout"])
        self.out = nn.Conv1d(widths[-1], out, 1)

    def forward(self, x):  # x (B, C, G)
        for i in range(self.n):
            block = getattr(self, str(i))
            x = self.drop(F.relu(block.bn(block.fc(x))))
        return self.out(x)


class JunctionNet(nn.Module):
    def __init__(self, c):
        super().__init__()
        self.lpt = LPT(c["lpt"])
        self.cls_head = Head(c["lpt"]["hidden_dim"], c["head"], 2)
        self.reg_head = Head(c["lpt"]["hidden_dim"], c["head"], 3)

    def forward(self, x, mask):
        f = self.lpt(x, mask).transpose(1, 2)  # (B, E, G)
        return self.cls_head(f).transpose(1, 2), self.reg_head(f).transpose(1, 2)


class EdgeNet(nn.Module):
    def __init__(self, c):
        super().__init__()
        self.lpt = LPT(c["lpt"])
        self.cls_head = Head(c["lpt"]["hidden_dim"], c["head"], c["num_classes"])

    def forward(self, x, mask):
        return self.cls_head(self.lpt(x, mask).transpose(1, 2)).transpose(1, 2)


# ------------------------------------------------------------------------------------------- losses
def junction_losses(logits, offsets, labels, target, reg_weight=10.0):
    cls = labels.to(offsets.dtype)
    per_building_den = cls.sum(dim=1) + 1e-8
    # release: softmax CE + L1 over positive patches, per-building mean then batch mean
    ce = F.cross_entropy(logits.reshape(-1, 2), labels.reshape(-1))
    l1 = ((offsets - target).abs().sum(-1) * cls).sum(1) / per_building_den
    release = (ce, reg_weight * l1.mean())
    # paper: BCE on z1 - z0 + squared error with the same weighting
    bce = F.binary_cross_entropy_with_logits(logits[..., 1] - logits[..., 0], cls)
    l2 = (((offsets - target) ** 2).sum(-1) * cls).sum(1) / per_building_den
    paper = (bce, reg_weight * l2.mean())
    return release, paper


# ---------------------------------------------------------------------------------------- exporting
def engine_state(model):
    """State dict under the engine's names: 1x1 conv kernels squeezed to (out, in), no batch counters."""
    out = {}
    for name, t in model.state_dict().items():
        if name.endswith("num_batches_tracked"):
            continue
        t = t.detach()
        if t.dim() > 2:
            t = t.reshape(t.shape[0], t.shape[1])
        out[name] = t.to(torch.float32).numpy().copy()
    return out


def load_engine_state(model, state):
    with torch.no_grad():
        for name, t in model.state_dict().items():
            if name.endswith("num_batches_tracked"):
                continue
            t.copy_(torch.from_numpy(state[name]).reshape(t.shape).to(t.dtype))


def grads(model):
    out = {}
    for name, p in model.named_parameters():
        g = p.grad.detach()
        if g.dim() > 2:
            g = g.reshape(g.shape[0], g.shape[1])
        out[name] = g.to(torch.float32).numpy().copy()
    return out


def f32(t):
    return t.detach().to(torch.float32).numpy().copy()


def make_mask(gen, B, G, N, pad_rate, full_patch):
    mask = torch.rand(B, G, N, generator=gen) < pad_rate
    mask[..., 0] = False  # like the release, the slot of the sample point's own segment is valid
    mask[full_patch] = True  # one fully padded patch (the engine must return zeros there, not NaN)
    return mask


def random_buffers(model, gen):
    with torch.no_grad():
        for name, t in model.named_buffers():
            if name.endswith("running_mean"):
                t.copy_(0.3 * torch.randn(t.shape, generator=gen))
            elif name.endswith("running_var"):
                t.copy_(0.5 + torch.rand(t.shape, generator=gen))


# ------------------------------------------------------------------------------------------- fixtures
SMALL_LPT = {"input_dim": 7, "lines_per_patch": 5, "patches": 6, "mlp_dims": [8, 8, 16, 16, 32], "hidden_dim": 32,
             "num_heads": 4, "ffn_dim": 32, "dropout": 0.0, "attn_dropout": 0.0, "line_layers": 2,
             "patch_layers": 1, "pool": "mean_all"}
SMALL_HEAD = {"dims": [16, 8, 8], "dropout": 0.0}


def check_attention_against_torch(gen):
    """Our reference attention equals torch.nn.MultiheadAttention whenever every query has a valid key."""
    torch.manual_seed(3)
    ours = Attention(32, 4, 0.0).double()
    theirs = nn.MultiheadAttention(32, 4, batch_first=True).double()
    with torch.no_grad():
        theirs.in_proj_weight.copy_(ours.in_proj_weight)
        theirs.in_proj_bias.copy_(ours.in_proj_bias + 0.1)
        ours.in_proj_bias.add_(0.1)
        theirs.out_proj.weight.copy_(ours.out_proj.weight)
        theirs.out_proj.bias.copy_(ours.out_proj.bias)
    x = torch.randn(3, 5, 32, generator=gen, dtype=torch.float64)
    mask = torch.rand(3, 5, generator=gen) < 0.4
    mask[:, 0] = False
    a = ours(x, mask)
    b = theirs(x, x, x, key_padding_mask=mask, need_weights=False)[0]
    err = (a - b).abs().max().item()
    if err > 1e-12:
        sys.exit(f"reference attention differs from torch.nn.MultiheadAttention by {err}")


def junction_small(out_dir):
    gen = torch.Generator().manual_seed(1555)
    torch.manual_seed(1555)
    cfg = {"lpt": dict(SMALL_LPT), "head": dict(SMALL_HEAD)}
    model = JunctionNet(cfg)
    init = engine_state(model)
    load_engine_state(model, init)  # weights rounded to float32, then the whole model in float64
    model = model.double().train()
    B, G, N = 3, 6, 5
    x = (0.3 * torch.randn(B, G, N, 7, generator=gen)).to(torch.float32)
    mask = make_mask(gen, B, G, N, 0.35, (1, 2))
    labels = torch.tensor([[1, 0, 1, 1, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 0, 0]], dtype=torch.int64)
    target = (0.2 * torch.randn(B, G, 3, generator=gen)).to(torch.float32)
    target[labels == 0] = 7.5  # arbitrary values on negative patches must not matter

    logits, offsets = model(x.double(), mask)
    (rce, rreg), (pbce, preg) = junction_losses(logits, offsets, labels, target.double())
    tensors = {f"init.{k}": v for k, v in init.items()}
    tensors.update({"input.x": f32(x), "input.mask": mask.numpy(), "target.labels": labels.numpy(),
                    "target.offsets": f32(target), "train.logits": f32(logits), "train.offsets": f32(offsets)})
    for k, v in engine_state(model).items():
        if "running" in k:
            tensors[f"train.after.{k}"] = v
    for tag, parts in (("release", (rce, rreg)), ("paper", (pbce, preg))):
        model.zero_grad()
        (parts[0] + parts[1]).backward(retain_graph=True)
        tensors[f"loss.{tag}.classification"] = f32(parts[0]).reshape(())
        tensors[f"loss.{tag}.regression"] = f32(parts[1]).reshape(())
        tensors[f"loss.{tag}.total"] = f32(parts[0] + parts[1]).reshape(())
        tensors.update({f"grad.{tag}.{k}": v for k, v in grads(model).items()})

    random_buffers(model, gen)
    model.eval()
    with torch.no_grad():
        logits, offsets = model(x.double(), mask)
    tensors.update({f"eval.state.{k}": v for k, v in engine_state(model).items()})
    tensors.update({"eval.logits": f32(logits), "eval.offsets": f32(offsets)})
    write_safetensors(os.path.join(out_dir, "junction_small.safetensors"), tensors, {"config": json.dumps(cfg)})


def edge_small(out_dir):
    gen = torch.Generator().manual_seed(77)
    torch.manual_seed(77)
    lpt = dict(SMALL_LPT, input_dim=6, lines_per_patch=8, patches=7, line_layers=1, patch_layers=2, pool="mean_valid")
    cfg = {"lpt": lpt, "head": dict(SMALL_HEAD), "num_classes": 5}
    model = EdgeNet(cfg)
    init = engine_state(model)
    load_engine_state(model, init)
    model = model.double().train()
    B, P, N = 2, 7, 8
    x = (0.3 * torch.randn(B, P, N, 6, generator=gen)).to(torch.float32)
    mask = make_mask(gen, B, P, N, 0.4, (0, 4))
    labels = torch.randint(0, 5, (B, P), generator=gen)
    labels[0, :3] = torch.tensor([1, 0, 4])
    weight = torch.tensor([1.0, 3.0, 1.0, 1.0, 1.0], dtype=torch.float64)
    logits = model(x.double(), mask)
    loss = F.cross_entropy(logits.reshape(-1, 5), labels.reshape(-1), weight=weight)
    loss.backward()
    tensors = {f"init.{k}": v for k, v in init.items()}
    tensors.update({"input.x": f32(x), "input.mask": mask.numpy(), "target.labels": labels.numpy(),
                    "train.logits": f32(logits), "loss.edge": f32(loss).reshape(())})
    tensors.update({f"grad.edge.{k}": v for k, v in grads(model).items()})
    for k, v in engine_state(model).items():
        if "running" in k:
            tensors[f"train.after.{k}"] = v
    random_buffers(model, gen)
    model.eval()
    with torch.no_grad():
        logits = model(x.double(), mask)
    tensors.update({f"eval.state.{k}": v for k, v in engine_state(model).items()})
    tensors["eval.logits"] = f32(logits)
    write_safetensors(os.path.join(out_dir, "edge_small.safetensors"), tensors, {"config": json.dumps(cfg)})


def full_size(out_dir):
    """Paper dimensions, eval mode, forward only. Weights follow hashed_value() so the file stays small."""
    gen = torch.Generator().manual_seed(2022)
    lpt_j = {"input_dim": 7, "lines_per_patch": 32, "patches": 256, "mlp_dims": [64, 64, 128, 128, 256],
             "hidden_dim": 256, "num_heads": 8, "ffn_dim": 256, "dropout": 0.5, "attn_dropout": 0.5,
             "line_layers": 1, "patch_layers": 1, "pool": "mean_all"}
    head = {"dims": [128, 64, 32], "dropout": 0.1}
    tensors = {}
    for kind, model, G, N, F_ in (("junction", JunctionNet({"lpt": lpt_j, "head": head}), 4, 32, 7),
                                  ("edge", EdgeNet({"lpt": dict(lpt_j, input_dim=6, lines_per_patch=64, patches=512),
                                                    "head": head, "num_classes": 5}), 5, 64, 6)):
        state = {k: hashed_value(k, list(v.shape)) for k, v in engine_state(model).items()}
        load_engine_state(model, state)
        model = model.double().eval()
        x = (0.3 * torch.randn(1, G, N, F_, generator=gen)).to(torch.float32)
        mask = make_mask(gen, 1, G, N, 0.5, (0, G - 1))
        with torch.no_grad():
            out = model(x.double(), mask)
        tensors[f"{kind}.x"] = f32(x)
        tensors[f"{kind}.mask"] = mask.numpy()
        if kind == "junction":
            tensors["junction.logits"], tensors["junction.offsets"] = f32(out[0]), f32(out[1])
        else:
            tensors["edge.logits"] = f32(out)
    write_safetensors(os.path.join(out_dir, "full_size_forward.safetensors"), tensors,
                      {"weights": "hashed_value(name): U(lo, hi) from Rng(fnv1a64(name)), see tools/make_golden.py"})


def optimizers(out_dir):
    """Three steps of AdamW and SGD with fixed gradients, with and without weight decay groups."""
    gen = torch.Generator().manual_seed(9)
    w0 = torch.randn(3, 4, generator=gen, dtype=torch.float64)
    b0 = torch.randn(4, generator=gen, dtype=torch.float64)
    g = [(torch.randn(3, 4, generator=gen, dtype=torch.float64), torch.randn(4, generator=gen, dtype=torch.float64))
         for _ in range(3)]
    tensors = {"init.layer.weight": f32(w0), "init.layer.bias": f32(b0)}
    for i, (gw, gb) in enumerate(g):
        tensors[f"grad{i}.layer.weight"], tensors[f"grad{i}.layer.bias"] = f32(gw), f32(gb)
    for name in ("adamw", "sgd"):
        w = torch.tensor(tensors["init.layer.weight"], dtype=torch.float64, requires_grad=True)
        b = torch.tensor(tensors["init.layer.bias"], dtype=torch.float64, requires_grad=True)
        groups = [{"params": [w], "weight_decay": 0.1}, {"params": [b], "weight_decay": 0.0}]
        opt = torch.optim.AdamW(groups, lr=0.01, betas=(0.9, 0.999), eps=1e-8) if name == "adamw" else \
            torch.optim.SGD(groups, lr=0.01, momentum=0.9)
        for i in range(3):
            w.grad = torch.tensor(tensors[f"grad{i}.layer.weight"], dtype=torch.float64)
            b.grad = torch.tensor(tensors[f"grad{i}.layer.bias"], dtype=torch.float64)
            opt.step()
            tensors[f"{name}.step{i}.layer.weight"], tensors[f"{name}.step{i}.layer.bias"] = f32(w), f32(b)
    write_safetensors(os.path.join(out_dir, "optimizers.safetensors"), tensors,
                      {"settings": "lr 0.01, weight_decay 0.1 on layer.weight only; AdamW betas 0.9/0.999 eps 1e-8; "
                                   "SGD momentum 0.9"})


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--out", default=os.path.join(here, "..", "tests", "data", "nn"), help="output folder")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    torch.set_num_threads(1)
    check_attention_against_torch(torch.Generator().manual_seed(5))
    junction_small(args.out)
    edge_small(args.out)
    full_size(args.out)
    optimizers(args.out)
    total = sum(os.path.getsize(os.path.join(args.out, f)) for f in os.listdir(args.out))
    print(f"wrote fixtures to {os.path.normpath(args.out)} ({total / 1024:.0f} KiB)")


if __name__ == "__main__":
    main()
