#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Summaries of sky-bench runs on the GPU machine (BENCHMARKS.md "Reproduce"), small enough to read from
# the device tool's output when it leaves files out.
#   summarize.py table LABEL=FILE.json ...   total (march) median ms per scene, one column per file
#   summarize.py clocks DIR ...              scene runs of DIR/log.txt during which DIR/clocks.csv shows
#                                            the SM clock below 1900 MHz (the GPU idled down: re-measure)
import json
import os
import re
import sys


def table(args):
    rows, labels = {}, []
    for arg in args:
        label, path = arg.split('=', 1)
        labels.append(label)
        try:
            doc = json.load(open(path))
        except (OSError, ValueError) as e:
            print(f'{label}: {e}')
            continue
        for scene in doc['scenes']:
            gpu = scene['gpuMs']
            total = gpu.get('total', {}).get('median')
            march = gpu.get('march', gpu.get('clouds', {})).get('median')
            rows.setdefault(scene['name'], {})[label] = (total, march)
    print('%-20s' % 'scene' + ''.join('%22s' % label for label in labels))
    for name, row in rows.items():
        cells = ''.join('%22s' % ('%.3f (m %.3f)' % row[l] if l in row and row[l][0] is not None else '-')
                        for l in labels)
        print('%-20s' % name + cells)


def clocks(dirs):
    for d in dirs:
        samples = []
        for line in open(os.path.join(d, 'clocks.csv')):
            fields = [f.strip() for f in line.split(',')]
            try:
                samples.append((fields[0].split()[1], int(fields[1].split()[0])))
            except (IndexError, ValueError):
                pass
        run = None
        for line in open(os.path.join(d, 'log.txt')):
            m = re.search(r'\] sky-bench (.*)', line)
            if m and 'rc=' not in line:
                run = m.group(1)
            m = re.search(r'sky-bench: (\S+)\s+\S+ done in .*UTC (\S+)\.\.(\S+)\)', line)
            if m:
                during = [mhz for t, mhz in samples if m.group(2) <= t <= m.group(3)]
                if during and min(during) < 1900:
                    print(f'{d}: {run}: {m.group(1)} ran at {min(during)} MHz at times')


if __name__ == '__main__':
    if len(sys.argv) < 3 or sys.argv[1] not in ('table', 'clocks'):
        sys.exit(__doc__ or 'usage: summarize.py table LABEL=FILE ... | clocks DIR ...')
    (table if sys.argv[1] == 'table' else clocks)(sys.argv[2:])
