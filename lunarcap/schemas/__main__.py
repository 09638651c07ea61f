"""``python -m lunarcap.schemas``: write the JSON Schemas generated from the glossary."""

from lunarcap.schemas import write

for _path in write():
    print(_path)
