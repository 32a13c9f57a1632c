#!/usr/bin/env python3
"""Every USB id the drivers know (device_ids.hpp) has a udev rule in
packaging/udev/70-palpa.rules, for the node the driver opens: hidraw for the SpaceMouse
family (hidapi), usb for the Falcon (libusb); every rule grants uaccess and plugdev."""
import argparse
import re
import sys
from pathlib import Path


def known_ids(header: str):
    """(vendor, product, model) from the UsbId initialisers of device_ids.hpp."""
    found = re.findall(r'\{\s*0x([0-9A-Fa-f]{4}),\s*0x([0-9A-Fa-f]{4}),\s*"([^"]+)"\s*\}', header)
    return [(v.lower(), p.lower(), m) for v, p, m in found]


def rules(text: str):
    """(kernel-or-subsystem, vendor, product, line) of every rule line."""
    out = []
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        vendor = re.search(r'ATTRS?\{idVendor\}=="([0-9a-f]{4})"', line)
        product = re.search(r'ATTRS?\{idProduct\}=="([0-9a-f]{4})"', line)
        node = "hidraw" if 'KERNEL=="hidraw*"' in line else "usb" if 'SUBSYSTEM=="usb"' in line else "?"
        if not vendor or not product:
            raise SystemExit(f"70-palpa.rules: rule without idVendor/idProduct: {line}")
        out.append((node, vendor.group(1), product.group(1), line))
    return out


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repo", required=True)
    repo = Path(parser.parse_args().repo)
    header = (repo / "device/include/palpa/device/device_ids.hpp").read_text()
    ids = known_ids(header)
    falcon = [i for i in ids if i[2] == "Novint Falcon"]
    spacemice = [i for i in ids if i[2] != "Novint Falcon"]
    if len(spacemice) != 7 or len(falcon) != 1:
        print(f"device_ids.hpp: expected 7 SpaceMouse ids and the Falcon, read {ids}", file=sys.stderr)
        return 1
    table = rules((repo / "packaging/udev/70-palpa.rules").read_text())
    failures = []
    for line in (r[3] for r in table):
        if 'TAG+="uaccess"' not in line or 'GROUP="plugdev"' not in line or 'MODE="0660"' not in line:
            failures.append(f"rule lacks uaccess, plugdev or 0660: {line}")
    have = {(node, v, p) for node, v, p, _ in table}
    for vendor, product, model in spacemice:
        for node in ("hidraw", "usb"):
            if (node, vendor, product) not in have:
                failures.append(f"{model} {vendor}:{product}: no {node} rule")
    for vendor, product, model in falcon:
        if ("usb", vendor, product) not in have:
            failures.append(f"{model} {vendor}:{product}: no usb rule")
    known = {(v, p) for v, p, _ in ids}
    for node, vendor, product, _ in table:
        if (vendor, product) not in known:
            failures.append(f"rule for {vendor}:{product}, which no driver knows")
    for f in failures:
        print("70-palpa.rules: " + f, file=sys.stderr)
    print(f"udev rules: {len(ids)} ids checked, {len(table)} rules, {len(failures)} problems")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
