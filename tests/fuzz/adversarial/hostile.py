"""Hostile variants of a valid input: truncations, bit flips, spliced bytes, extreme numbers (NaN, Inf,
huge counts and coordinates), NUL and non-UTF-8 bytes, repeated lines. Deterministic for a given rng."""
import re

# Numbers a reader must refuse or survive: NaN/Inf spellings, overflowing integers and doubles, counts that
# exceed any file, coordinates beyond the +-1e9 limit, denormals, hex.
EXTREME_NUMBERS = [
    b"nan", b"NaN", b"-nan", b"inf", b"-inf", b"Infinity", b"1e308", b"1e309", b"-1e400", b"1e-320",
    b"99999999999999999999", b"9223372036854775807", b"9223372036854775808", b"-9223372036854775809",
    b"4294967296", b"4294967298", b"2147483648", b"-1", b"0", b"-0", b"1000000000", b"1e18", b"6e8", b"1e300",
    b"0.5", b"0x10", b"1e", b"+", b"--1", b"1.5e3x",
]
NUMBER = re.compile(rb"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def truncations(data, rng, count):
    cuts = {0, 1, len(data) // 2, max(len(data) - 1, 0)}
    while len(cuts) < count + 4 and len(cuts) < len(data):
        cuts.add(rng.randrange(len(data)))
    return [data[:c] for c in sorted(cuts)][:count]


def bit_flips(data, rng, flips):
    b = bytearray(data)
    for _ in range(flips):
        if b:
            b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
    return bytes(b)


def splice(data, rng):
    """Deletes, duplicates or inserts junk at a random place."""
    if not data:
        return bytes(rng.randrange(256) for _ in range(16))
    i = rng.randrange(len(data))
    j = min(len(data), i + rng.randrange(1, 64))
    kind = rng.randrange(3)
    if kind == 0:
        return data[:i] + data[j:]
    if kind == 1:
        return data[:j] + data[i:j] * rng.randrange(2, 50) + data[j:]
    return data[:i] + bytes(rng.randrange(256) for _ in range(rng.randrange(1, 32))) + data[i:]


def number_swap(data, rng, swaps=1):
    """Replaces random numbers of the text with extreme ones."""
    spans = [m.span() for m in NUMBER.finditer(data)]
    if not spans:
        return data + rng.choice(EXTREME_NUMBERS)
    out = data
    for a, b in sorted(rng.sample(spans, min(swaps, len(spans))), reverse=True):
        out = out[:a] + rng.choice(EXTREME_NUMBERS) + out[b:]
    return out


def all_numbers(data, value):
    """Every number of the text replaced by one value (huge coordinates, NaN everywhere)."""
    return NUMBER.sub(lambda m: value, data)


def inject(data, rng, junk):
    i = rng.randrange(len(data) + 1)
    return data[:i] + junk + data[i:]


NON_UTF8 = [b"\xff", b"\xfe\xff", b"\xc3\x28", b"\xed\xa0\x80", b"\xf8\x88\x80\x80\x80", b"\x80"]


def repeat_line(data, rng, times):
    lines = data.split(b"\n")
    k = rng.randrange(len(lines))
    return b"\n".join(lines[:k] + [lines[k]] * times + lines[k + 1:])


def variants(data, rng, count):
    """`count` hostile versions of `data`, mixing every kind above."""
    out = truncations(data, rng, max(2, count // 8))
    makers = [
        lambda: bit_flips(data, rng, rng.choice([1, 2, 8, 64])),
        lambda: splice(data, rng),
        lambda: number_swap(data, rng, rng.choice([1, 1, 3, 20])),
        lambda: all_numbers(data, rng.choice([b"1e300", b"nan", b"-1", b"99999999999", b"6e8", b"0"])),
        lambda: inject(data, rng, rng.choice(NON_UTF8)),
        lambda: inject(data, rng, b"\x00" * rng.choice([1, 7])),
        lambda: inject(data, rng, b'"\\u0000../../escape"'),
        lambda: repeat_line(data, rng, rng.choice([2, 1000])),
    ]
    while len(out) < count:
        out.append(rng.choice(makers)())
    return out[:count]
