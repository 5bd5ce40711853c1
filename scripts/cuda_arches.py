#!/usr/bin/python3
"""Lists the GPU code an executable or library embeds: one line per kind,
e.g. "elf sm_90: 412 images" and "ptx compute_90: 206 images", like
`cuobjdump --list-elf / --list-ptx` (which the CUDA wheels on these machines
do not ship).

It reads the ELF file's .nv_fatbin section: fat binaries, each a 16-byte
header (magic 0xBA55ED50, version u16, header size u16, payload size u64)
followed by entries whose header holds kind (u16 at 0: 1 PTX, 2 cubin ELF),
header size (u32 at 4), payload size (u64 at 8) and the target arch (u32 at
28). Layout checked against nvcc 13.0 outputs for sm_75, sm_80, sm_90 and a
compute_86 PTX entry.

usage: cuda_arches.py FILE [--require sm_90]   (exit 1 if that ELF code is missing)
"""
import collections
import struct
import sys

FATBIN_MAGIC = 0xBA55ED50
KINDS = {1: "ptx", 2: "elf"}


def sections(data):
    if data[:4] != b"\x7fELF" or data[4] != 2:
        raise ValueError("not a 64-bit ELF file")
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
    headers = [struct.unpack_from("<IIQQQQ", data, shoff + i * shentsize) for i in range(shnum)]
    names_offset = headers[shstrndx][4]
    for name, _type, _flags, _addr, offset, size in headers:
        end = data.index(b"\0", names_offset + name)
        yield data[names_offset + name:end].decode(), offset, size


def embedded_arches(data):
    """Counter of (kind, arch) over every fat binary of the .nv_fatbin section."""
    found = collections.Counter()
    for name, offset, size in sections(data):
        if name != ".nv_fatbin":
            continue
        pos, end = offset, offset + size
        while pos + 16 <= end:
            magic, _version, header_size, fat_size = struct.unpack_from("<IHHQ", data, pos)
            if magic != FATBIN_MAGIC:
                pos += 8  # fat binaries are 8-byte aligned in the section
                continue
            entry, entries_end = pos + header_size, pos + header_size + fat_size
            while entry < entries_end:
                kind, _v, entry_header, payload = struct.unpack_from("<HHIQ", data, entry)
                arch, = struct.unpack_from("<I", data, entry + 28)
                found[(KINDS.get(kind, f"kind{kind}"), arch)] += 1
                entry += entry_header + payload
            pos = entries_end
    return found


def main(argv):
    if len(argv) not in (2, 4) or (len(argv) == 4 and argv[2] != "--require"):
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    with open(argv[1], "rb") as f:
        found = embedded_arches(f.read())
    for (kind, arch), count in sorted(found.items()):
        prefix = "sm" if kind == "elf" else "compute"
        print(f"{kind} {prefix}_{arch}: {count} images")
    if len(argv) == 4:
        wanted = int(argv[3].removeprefix("sm_"))
        if found[("elf", wanted)] == 0:
            print(f"{argv[1]}: no sm_{wanted} ELF code", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
