"""Each kernel is called with one argument type per parameter, as far as the source shows it.

numba compiles a kernel once per combination of argument types it is called with, and each
compilation of a large kernel costs seconds on an empty cache (the CI's default run compiles
for about two minutes, docs/development.md#numba-compile-time). Two kinds of mismatch are
visible in the source and cost a whole second compilation of the kernel and of everything it
calls:

- a Python literal (``0``, ``True``) passed by a kernel: numba types it as that literal value,
  so ``f(x, 0)`` beside ``f(x, 1)`` or ``f(x, k)`` compiles ``f`` twice or more (pass a typed
  value, ``np.int64(0)``, ``np.bool_(True)``, or the same literal everywhere);
- an optional parameter (``fa=None``) left out at one call and given (``None`` or an array) at
  another: "omitted" is a type of its own, beside ``none``.

The test reads the package's kernel modules and the tests (which call kernels from Python: an
omitted argument counts there too) without importing them, and fails on a mismatch not listed
in :data:`KNOWN`, naming the kernel, the parameter and the calls. Not visible here: a read-only
array beside a writable one (it depends on the values), and a counter that starts at a literal
(``n = 0`` before a loop that adds to it), which numba may type as the literal first and compile
for it too (start it at a typed zero, as ``dgi_run_path`` does).
"""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

from tests.package_source import PACKAGE, REPO, TESTS

#: What marks a kernel (floatmoor._numba.KERNEL_MARK).
KERNEL_DECORATOR = "jit"

#: Mismatches known and accepted for now: (module, kernel, parameter). They sit in kernel
#: modules being changed by other work (the single line's implicit kernels); each costs well
#: under a second of compiling.
KNOWN = frozenset({
    ("floatmoor.mooring.dg._implicit_kernels", "_end_gradient", "c"),
    ("floatmoor.mooring.dg._implicit_kernels", "_add_diagonal", "col_node"),
})


def _module_name(path: Path) -> str:
    return ".".join(path.relative_to(REPO).with_suffix("").parts)


def _is_kernel(node: ast.AST) -> bool:
    if not isinstance(node, ast.FunctionDef):
        return False
    for dec in node.decorator_list:
        target = dec.func if isinstance(dec, ast.Call) else dec
        if isinstance(target, ast.Name) and target.id == KERNEL_DECORATOR:
            return True
    return False


def _inlined(node: ast.FunctionDef) -> bool:
    """A kernel numba inlines into its callers (``@jit(inline="always")``): typed at each
    call, never compiled on its own."""
    return any(isinstance(dec, ast.Call) and any(k.arg == "inline" for k in dec.keywords)
               for dec in node.decorator_list)


def _kernels(paths: list[Path]) -> dict[tuple[str, str], ast.FunctionDef]:
    """Every kernel of the package compiled on its own: (module, name) -> its definition."""
    found = {}
    for path in paths:
        tree = ast.parse(path.read_text())
        for node in tree.body:
            if _is_kernel(node) and not _inlined(node):
                found[(_module_name(path), node.name)] = node
    return found


def _aliases(tree: ast.Module) -> tuple[dict[str, str], dict[str, tuple[str, str]]]:
    """Names bound to floatmoor modules (``_k`` -> its module) and to functions imported from
    them (``band_solve`` -> (module, name)), at module level."""
    modules, names = {}, {}
    for node in tree.body:
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith(
                "floatmoor"):
            for alias in node.names:
                full = f"{node.module}.{alias.name}"
                if (PACKAGE.parent / Path(*full.split("."))).with_suffix(".py").is_file():
                    modules[alias.asname or alias.name] = full
                else:
                    names[alias.asname or alias.name] = (node.module, alias.name)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("floatmoor") and alias.asname:
                    modules[alias.asname] = alias.name
    return modules, names


def _argument_kind(node: ast.expr, literal_counts: bool) -> str:
    """How numba types a call argument: ``literal <value>`` (a constant passed by a kernel),
    ``none`` or ``value``."""
    if isinstance(node, ast.Constant):
        if node.value is None:
            return "none"
        if literal_counts and isinstance(node.value, (bool, int)):
            return f"literal {node.value!r}"
    return "value"


def _own_calls(node: ast.AST):
    """The calls in ``node``'s body, not in the kernels defined inside it."""
    for child in ast.iter_child_nodes(node):
        if _is_kernel(child):
            continue
        if isinstance(child, ast.Call):
            yield child
        yield from _own_calls(child)


def _calls(files: list[tuple[Path, str | None]],
           kernels: dict[tuple[str, str], ast.FunctionDef]):
    """Every call of a kernel in ``files`` ((file, its module name or None)):
    (kernel, parameter) -> {argument kind: [where]}."""
    uses: dict[tuple[tuple[str, str], str], dict[str, list[str]]] = defaultdict(
        lambda: defaultdict(list))
    for path, module in files:
        tree = ast.parse(path.read_text())
        modules, names = _aliases(tree)
        scopes = [(tree, False)] + [(n, True) for n in ast.walk(tree) if _is_kernel(n)]
        for scope, in_kernel in scopes:
            for node in _own_calls(scope):
                func, target = node.func, None
                if isinstance(func, ast.Name):
                    target = names.get(func.id) or (module, func.id)
                elif isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name):
                    if func.value.id in modules:
                        target = (modules[func.value.id], func.attr)
                if target not in kernels:
                    continue
                if any(isinstance(a, ast.Starred) for a in node.args) or any(
                        k.arg is None for k in node.keywords):
                    continue  # (*args, **kwargs: not followed)
                params = kernels[target].args
                param_names = [a.arg for a in params.args]
                first_default = len(param_names) - len(params.defaults)
                given = {param_names[i]: a for i, a in enumerate(node.args)}
                given.update({k.arg: k.value for k in node.keywords})
                where = f"{path.name}:{node.lineno}"
                for i, name in enumerate(param_names):
                    if name in given:
                        kind = _argument_kind(given[name], in_kernel)
                    elif i >= first_default:
                        kind = "omitted"
                    else:
                        continue
                    uses[(target, name)][kind].append(where)
    return uses


def _mismatches(uses) -> dict[tuple[str, str, str], dict[str, list[str]]]:
    """The (module, kernel, parameter) whose calls compile more than one type for a literal
    or an omitted argument."""
    found = {}
    for ((module, kernel), param), kinds in uses.items():
        literal = any(k.startswith("literal") for k in kinds)
        if len(kinds) > 1 and (literal or "omitted" in kinds):
            found[(module, kernel, param)] = kinds
    return found


def _sources() -> tuple[list[Path], list[Path]]:
    """The package's module files and the tests' files."""
    package = [p for p in sorted(PACKAGE.rglob("*.py")) if "__pycache__" not in p.parts]
    # (the timings of tests/benchmarks, not in the default run, are left out)
    tests = [p for p in sorted(TESTS.rglob("*.py"))
             if "__pycache__" not in p.parts and "benchmarks" not in p.parts]
    return package, tests


def test_the_finder_sees_planted_mismatches(tmp_path: Path) -> None:
    """A literal beside a typed value, two literals, and an optional parameter omitted beside
    None are found; one literal everywhere, and None beside an array, are not; a literal
    passed from Python (typed as a plain int) is no mismatch."""
    path = tmp_path / "planted.py"
    path.write_text('''
from floatmoor._numba import jit

@jit
def _leaf(a, k, flag, same, fa=None):
    return a

@jit
def caller(a, k, fa):
    _leaf(a, 0, True, 2, None)
    _leaf(a, k, True, 2, fa)
    _leaf(a, 1, False, 2, None)

@jit(inline="always")
def _inlined(a, k):
    return a

@jit
def other(a):
    _inlined(a, 0)
    _inlined(a, 1)

def from_python(a):
    caller(a, 0, None)
    caller(a, 1, None)
''')
    tree = ast.parse(path.read_text())
    kernels = {("planted", n.name): n for n in tree.body if _is_kernel(n)}
    found = _mismatches(_calls([(path, "planted")], kernels))
    assert {key[2] for key in found} == {"k", "flag"}
    path.write_text(path.read_text() + "\n@jit\ndef late(a, k):\n    _leaf(a, k, True, 2)\n")
    found = _mismatches(_calls([(path, "planted")], kernels))
    assert {key[2] for key in found} == {"k", "flag", "fa"}


def test_kernels_get_one_type_per_parameter_at_every_call() -> None:
    """No kernel of the package is called with a literal beside another type, or with an
    optional argument omitted beside given, outside :data:`KNOWN`."""
    package, tests = _sources()
    kernels = _kernels(package)
    assert len(kernels) > 50  # (the finder sees the package's kernels)
    files = [(p, _module_name(p)) for p in package] + [(p, None) for p in tests]
    found = _mismatches(_calls(files, kernels))
    new = {key: dict(kinds) for key, kinds in found.items() if key not in KNOWN}
    assert not new, "\n".join(
        f"{m}.{k}, parameter {p}: " + "; ".join(f"{kind} at {', '.join(w)}"
                                                for kind, w in kinds.items())
        for (m, k, p), kinds in sorted(new.items()))
    # a mismatch fixed leaves KNOWN
    assert KNOWN <= set(found), sorted(KNOWN - set(found))
