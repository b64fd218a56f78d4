#!/usr/bin/env python3
# Decodes an 8-bit, non-interlaced RGB or RGBA PNG (PNG specification, W3C 2003: chunks, zlib
# stream, the five scanline filters) and writes it as a binary PPM (P6), alpha composited over
# white, so the C++ test can read the pixels rsvg-convert drew. Standard library only.
#   png_to_ppm.py IN.png OUT.ppm
import struct
import sys
import zlib


def main(source, target):
    data = open(source, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("not a PNG: " + source)
    pos, idat, header = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        sys.exit("unsupported PNG layout (depth %d, colour type %d, interlace %d)" % (depth, colour, interlace))
    bpp = 3 if colour == 2 else 4
    raw = zlib.decompress(b"".join(idat))
    stride = width * bpp
    previous = bytearray(stride)
    out = bytearray()
    for y in range(height):
        start = y * (stride + 1)
        kind = raw[start]
        line = bytearray(raw[start + 1:start + 1 + stride])
        if kind == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif kind == 2:
            line = bytearray((a + b) & 255 for a, b in zip(line, previous))
        elif kind == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + previous[i]) >> 1)) & 255
        elif kind == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = previous[i]
                c = previous[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                predictor = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + predictor) & 255
        elif kind != 0:
            sys.exit("bad filter type %d in row %d" % (kind, y))
        previous = line
        if bpp == 3:
            out += line
        else:
            for i in range(0, stride, 4):
                alpha = line[i + 3]
                for k in range(3):
                    out.append((line[i + k] * alpha + 255 * (255 - alpha) + 127) // 255)
    with open(target, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (width, height))
        f.write(out)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
