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
