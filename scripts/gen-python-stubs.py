#!/usr/bin/env python3
"""Write python/oscidrum/__init__.pyi, the type stubs of the package, from the compiled module's
pybind11 signatures and the field table (run after changing a binding):

    PYTHONPATH=build/python /usr/bin/python3 scripts/gen-python-stubs.py
"""

import enum
import inspect
import pathlib
import re

import oscidrum
from oscidrum import _core

OUT = pathlib.Path(__file__).resolve().parent.parent / "python" / "oscidrum" / "__init__.pyi"
PY_TYPES = {"real": "float", "integer": "int", "boolean": "bool", "choice": "str"}


def clean(text):
    text = text.replace("oscidrum._core.", "").replace("numpy.ndarray[numpy.float64]",
                                                       "numpy.ndarray")
    text = re.sub(r"numpy\.ndarray\[[^\]]*\]", "numpy.ndarray", text)
    text = text.replace("Callable[[int, int], None]", "Callable[[int, int], Any]")
    # A method that reads its Python object (a parameter group judged in its case) takes
    # self as a handle: the stub's self needs no annotation.
    text = text.replace("(self: handle", "(self")
    text = re.sub(r":\s*handle\b", ": Any", text)  # any Python object
    text = re.sub(r"\bobject\b", "Any", text)
    text = re.sub(r"=\s*<[^>]*>", "= ...", text)
    text = re.sub(r"= (None|True|False|-?[0-9.e+-]+|'[^']*')", "= ...", text)
    text = re.sub(r"\*\*kwargs\b(?!:)", "**kwargs: Any", text)
    text = re.sub(r"\*args\b(?!:)", "*args: Any", text)
    return text


def signatures(func, name):
    func = inspect.unwrap(func)
    if inspect.isfunction(func):  # pure Python (e.g. Result.to_dataframe)
        return [f"{name}(self) -> Any" if "self" in inspect.signature(func).parameters
                else f"{name}{inspect.signature(func)}"]
    doc = func.__doc__ or ""
    sigs = [] if "Overloaded function" in doc else [
        line.strip() for line in doc.splitlines() if line.strip().startswith(name + "(")]
    if not sigs:
        sigs = [re.sub(r"^\d+\. ", "", line.strip()) for line in doc.splitlines()
                if re.match(r"^\d+\. " + re.escape(name) + r"\(", line.strip())]
    return [clean(s) for s in sigs] or [f"{name}(*args: Any, **kwargs: Any) -> Any"]


def emit_function(lines, func, name, indent="", static=False):
    sigs = signatures(func, name)
    for s in sigs:
        if len(sigs) > 1:
            lines.append(f"{indent}@overload")
        if static:
            lines.append(f"{indent}@staticmethod")
        if "->" not in s:
            s += " -> None"
        lines.append(f"{indent}def {s}: ...")


def field_props(cls):
    group = {"Roller": "roller.", "Soil": "soil.", "Trough": "trough.", "Contact": "contact.",
             "Numerics": "numerics."}.get(cls.__name__)
    if group is None:
        return {}
    return {f.key[len(group):]: PY_TYPES[f.type] for f in oscidrum.fields()
            if f.key.startswith(group)}


def emit_class(lines, cls):
    bases = "enum.IntEnum" if hasattr(cls, "__members__") else ""
    lines.append(f"class {cls.__name__}{'(' + bases + ')' if bases else ''}:")
    typed = field_props(cls)
    if cls is _core.Case:
        typed = {"roller": "Roller", "soil": "Soil", "trough": "Trough", "contact": "Contact",
                 "numerics": "Numerics", "MMd": "float"}
    body = []
    if hasattr(cls, "__members__"):
        for m in cls.__members__:
            body.append(f"    {m} = {int(cls.__members__[m])}")
    for name, attr in sorted(vars(cls).items()):
        if name.startswith("_") and name not in ("__init__", "__len__", "__getstate__",
                                                 "__setstate__"):
            continue
        if hasattr(cls, "__members__") and name in cls.__members__:
            continue
        if isinstance(attr, property):
            doc = (attr.__doc__ or "").strip()
            ret = typed.get(name)
            if ret is None and attr.fget is not None:
                m = re.search(r"->\s*([^\n:]+)", attr.fget.__doc__ or "")
                ret = clean(m.group(1).strip()) if m else "Any"
            body.append(f"    {name}: {ret}")
            if doc:
                body.append(f"    \"\"\"{doc.splitlines()[0].replace(chr(92), '/')}\"\"\"")
        elif isinstance(attr, staticmethod):
            emit_function(body, attr.__func__, name, "    ", static=True)
        elif callable(attr) or type(attr).__name__ == "instancemethod":
            func = getattr(attr, "__func__", attr)
            func = getattr(func, "__wrapped__", func)
            emit_function(body, func, name, "    ")
        elif not callable(attr) and not name.startswith("_"):
            if type(attr).__name__ == "pybind11_static_property" or True:
                body.append(f"    {name}: Any")
    if cls is _core.Case:
        # The keyword of each key (its alias) and of each group (a dict or the group's object).
        groups = ("contact", "numerics", "roller", "soil", "trough")
        kw = ", ".join(f"{a}: Any = ..." for a in sorted(set(_core.Case.aliases()) | set(groups)))
        body.insert(0, f"    def __init__(self, *, R: float = ..., {kw}, **dotted: Any) -> None: ...")
        body = [b for b in body if not b.startswith("    def __init__(*args")]
    elif field_props(cls):
        body = [f"    def __init__(self, **kwargs: Any) -> None: ..." if b.startswith(
            "    def __init__(*args") else b for b in body]
    body = [b.replace("def __setstate__(*args: Any, **kwargs: Any) -> Any",
                      "def __setstate__(self, state: Any) -> None") for b in body]
    lines.extend(body or ["    ..."])
    lines.append("")


def main():
    lines = ['"""Type stubs of oscidrum (generated by scripts/gen-python-stubs.py)."""', "",
             "import enum", "import os", "from typing import Any, Callable, Dict, Iterable, List, "
             "Optional, Sequence, Tuple, Union, overload", "", "import numpy", "",
             "from .study import Interrupted as Interrupted, StudyResult as StudyResult, "
             "run_study as run_study", "", "__version__: str", "",
             "class Error(ValueError):",
             "    key: Optional[str]",
             '    """the dotted key of the parameter at fault (e.g. "soil.G"), else None"""',
             "    value: Any",
             '    """the number received, when a number was refused, else None"""', ""]
    names = [n for n in oscidrum._CORE_NAMES if n not in ("Error", "__version__")]
    classes = [getattr(_core, n) for n in names if isinstance(getattr(_core, n), type)]
    for cls in classes:
        emit_class(lines, cls)
    for n in names:
        obj = getattr(_core, n)
        if not isinstance(obj, type):
            emit_function(lines, obj, n)
    text = "\n".join(lines) + "\n"
    text = text.replace("load_case(path: Any)", "load_case(path: Union[str, os.PathLike])")
    text = text.replace("read_record(path: Any,", "read_record(path: Union[str, os.PathLike],")
    compile(text, str(OUT), "exec")
    OUT.write_text(text)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
