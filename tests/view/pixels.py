"""tests/view/pixels.py PNG X0 Y0 X1 Y1 RRGGBB - how many pixels of the
rectangle [X0, X1) x [Y0, Y1) of an 8-bit RGB or RGBA PNG (a Chromium
screenshot) differ from the colour RRGGBB by more than 24 in some channel.
Only the standard library (zlib): the PNG is decoded here, filters and all.
Prints the count; exit 2 on a PNG it cannot read."""
import struct
import sys
import zlib


def decode(path):
    """(width, height, channels, rows): rows[y] is a bytes of width*channels."""
    with open(path, 'rb') as f:
        blob = f.read()
    if blob[:8] != b'\x89PNG\r\n\x1a\n':
        raise ValueError('not a PNG')
    pos, idat = 8, []
    while pos < len(blob):
        size, kind = struct.unpack('>I4s', blob[pos:pos + 8])
        body = blob[pos + 8:pos + 8 + size]
        if kind == b'IHDR':
            w, h, depth, ctype, _, _, interlace = struct.unpack('>IIBBBBB', body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                raise ValueError('only 8-bit RGB/RGBA, not interlaced')
            ch = 3 if ctype == 2 else 4
        elif kind == b'IDAT':
            idat.append(body)
        pos += 12 + size
    raw = zlib.decompress(b''.join(idat))
    stride = w * ch
    rows, prev = [], bytearray(stride)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if ft == 1:
            for i in range(ch, stride):
                line[i] = (line[i] + line[i - ch]) & 255
        elif ft == 2:
            line = bytearray((a + b) & 255 for a, b in zip(line, prev))
        elif ft == 3:
            for i in range(stride):
                left = line[i - ch] if i >= ch else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif ft == 4:
            for i in range(stride):
                a = line[i - ch] if i >= ch else 0
                b, c = prev[i], prev[i - ch] if i >= ch else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else b if pb <= pc else c
                line[i] = (line[i] + pred) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, ch, rows


def main():
    path, x0, y0, x1, y1, colour = sys.argv[1:7]
    x0, y0, x1, y1 = (int(float(v)) for v in (x0, y0, x1, y1))
    bg = [int(colour[i:i + 2], 16) for i in (0, 2, 4)]
    try:
        w, h, ch, rows = decode(path)
    except (OSError, ValueError, zlib.error) as err:
        print('pixels.py: %s: %s' % (path, err), file=sys.stderr)
        sys.exit(2)
    count = 0
    for y in range(max(0, y0), min(h, y1)):
        row = rows[y]
        for x in range(max(0, x0), min(w, x1)):
            px = row[x * ch:x * ch + 3]
            if max(abs(px[k] - bg[k]) for k in range(3)) > 24:
                count += 1
    print(count)


main()
