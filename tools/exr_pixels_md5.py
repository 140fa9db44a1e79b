#!/usr/bin/env python3
"""MD5 of the pixels of single-part scanline OpenEXR files (tools/snapshot.sh).

The header is skipped but for the channel list, data window and compression: shadowlab writes
the command line, the commit and the date into it, which differ between runs of equal images.
The chunks (compressed deterministically) are hashed after the line offset table, whose values
depend on the header length. Usage: exr_pixels_md5.py FILE.exr... (one digest per line).
"""
import hashlib, struct, sys
LINES = {0: 1, 1: 1, 2: 1, 3: 16, 4: 32, 5: 16, 6: 32, 7: 32, 8: 32, 9: 256}
def pixels_md5(path):
    b = open(path, 'rb').read()
    assert b[:4] == b'\x76\x2f\x31\x01', 'not an EXR'
    flags = struct.unpack_from('<I', b, 4)[0]
    assert flags & 0x200 == 0 and flags & 0x1000 == 0, 'tiled or multipart'
    p = 8
    attrs = {}
    while b[p] != 0:
        e = b.index(b'\0', p); name = b[p:e].decode(); p = e + 1
        e = b.index(b'\0', p); p = e + 1
        size = struct.unpack_from('<i', b, p)[0]; p += 4
        attrs[name] = b[p:p + size]; p += size
    p += 1
    xmin, ymin, xmax, ymax = struct.unpack('<4i', attrs['dataWindow'])
    per = LINES[attrs['compression'][0]]
    chunks = (ymax - ymin + per) // per
    h = hashlib.md5()
    h.update(attrs['channels']); h.update(attrs['dataWindow']); h.update(attrs['compression'])
    h.update(b[p + 8 * chunks:])
    return h.hexdigest()
for f in sys.argv[1:]:
    print(pixels_md5(f))
