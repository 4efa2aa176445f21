#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_asterix_decode (fuzz/corpus/asterix_decode/): data blocks as
skyfuse's encoders write them (the bytes tests/unit/asterix/ check item by item), a datagram of
all three categories, and a few broken on purpose. Run from the repository root."""
from pathlib import Path

# Two CAT062 ed. 1.19 tracks: every item the encoder writes (010 015 070 105 100 185 060 380/ADR
# 040 080 in 4 octets 130 500), then the minimal one.
CAT062 = bytes.fromhex(
    "3E0054BF5D1104196401587840FF800000FF000000FFF82F001389FE1F01010E53804CA2B310922301018006"
    "40D40019000EFFF7100402BF0C19640000320000927D28FFFE93E90000000000000000000000000700")
# A CAT048 ed. 1.31 plot: 010 140 020 (with TST) 040 070 090 220 161.
CAT048 = bytes.fromhex("300019FD90190A587840A18064004000029C05783C65860BB8")
# A CAT021 ed. 2.6 report: 010 040 071 130 131 080 073 140 090 (two extensions) 160.
CAT021 = bytes.fromhex(
    "15002BCF196108190B0100587840E00000C00000F0000000E0000000A1B2C3587860064051F31204722000")

SEEDS = {
    "cat062.bin": CAT062,
    "cat048.bin": CAT048,
    "cat021.bin": CAT021,
    "all_three.bin": CAT062 + CAT048 + CAT021,
    "len_past_end.bin": CAT048[:-1],
    "unknown_category.bin": bytes([1, 0, 5, 0x80, 0]) + CAT048,
    "fspec_open.bin": bytes([62, 0, 4, 0xFF]),
}

out = Path("fuzz/corpus/asterix_decode")
out.mkdir(parents=True, exist_ok=True)
for name, data in SEEDS.items():
    (out / name).write_bytes(data)
