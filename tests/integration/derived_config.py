"""A workflow config read for a test or bench that changes it and writes
it elsewhere: the files it names relative to itself (a material's
potential_file) made absolute, so that the copy finds them."""
import os

import yaml

FILE_KEYS = ("potential_file",)


def load(path):
    config = yaml.safe_load(open(path))
    here = os.path.dirname(os.path.abspath(path))
    for material in (config.get("materials") or {}).values():
        for key in FILE_KEYS:
            if key in material and not os.path.isabs(material[key]):
                material[key] = os.path.join(here, material[key])
    return config


def cut_box(stage, axis, below, above):
    """Cuts a concurrent stage's box and grid by whole cells along `axis`:
    the bodies (their pieces and the groups' regions) move `below` cells
    down, and `below + above` cells come off the top. A test runs the same
    bodies in less gas."""
    h = stage["grid"]["cell_size"]
    stage["box"]["hi"][axis] -= (below + above) * h
    stage["grid"]["cells"][axis] -= below + above
    for piece in stage["initial"]["pieces"]:
        piece["shift"][axis] -= below * h
    for group in stage["groups"]:
        region = group["region"]
        if region["style"] == "sphere":
            region["centre"][axis] -= below * h
            continue
        # A cylinder's centre holds the two axes across it.
        across = [a for a in range(3) if a != "xyz".index(region["axis"])]
        if axis in across:
            region["centre"][across.index(axis)] -= below * h
        else:
            region["lo"] -= below * h
            region["hi"] -= below * h
