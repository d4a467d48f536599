"""The code-writing parts every generated formula module shares: sympy's numpy printer,
formulas as functions with common subexpressions (sympy ``cse``) and long parts on lines
of their own, lookup tables of those functions, and the hand-written runtime a module
copies (a real module of this package, so it is linted and type-checked; the generated
module only adds data and formulas where its placeholders stand)."""

from __future__ import annotations

import ast
import importlib
import inspect
import keyword
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from functools import cache
from types import ModuleType

import sympy
from sympy.printing.numpy import NumPyPrinter

from davies_sym.emit.code_layout import WIDTH, docstring, keyword_function, literal, module_source
from davies_sym.errors import DerivationError, TopologyError
from davies_sym.topology.model import Train

_TEMPORARY = "_t"
#: Room for one printed expression: the width less an indent, ``_t12 = `` and ``_array(...)``.
_BUDGET = WIDTH - 30


#: numpy's names of functions the array API standard names otherwise.
_ARRAY_API_NAMES = {
    "arccos": "acos",
    "arcsin": "asin",
    "arctan": "atan",
    "arctan2": "atan2",
    "arccosh": "acosh",
    "arcsinh": "asinh",
    "arctanh": "atanh",
    "absolute": "abs",
    "power": "pow",
}


class _Printer(NumPyPrinter):  # type: ignore[misc]  # sympy has no type information
    """Array API code: sympy's numpy printer with each function taken from ``xp``, the
    namespace of the arguments (numpy, or the library of the arrays given), under the
    standard's name."""

    def _module_format(self, fqn: str, register: bool = True) -> str:
        name = str(super()._module_format(fqn, register))
        if not name.startswith("numpy."):
            return name
        function = name[len("numpy.") :]
        return "xp." + _ARRAY_API_NAMES.get(function, function)


def _code(expr: sympy.Basic) -> str:
    return str(_Printer({"fully_qualified_modules": True}).doprint(expr))


def parsed(expr: sympy.Basic) -> ast.expr:
    """The printer's code of ``expr`` as a node."""
    return ast.parse(_code(expr), mode="eval").body


def _width(expr: sympy.Basic) -> int:
    """Characters of ``expr`` as the module writes it (``ast.unparse`` spaces the operators)."""
    return len(ast.unparse(parsed(expr)))


def name_node(text: str) -> ast.Name:
    return ast.Name(text, ast.Load())


def call(function: str, *args: ast.expr) -> ast.Call:
    return ast.Call(name_node(function), list(args), [])


@dataclass(frozen=True)
class Runtime:
    """The parts of a runtime module: the import block and, in order, the source of every
    other top-level statement (placeholders: their name and annotation); and the names it
    defines or imports, which a train's names may not take."""

    imports: str
    before: tuple[str, ...]
    placeholders: dict[str, ast.expr]
    after: tuple[str, ...]
    names: frozenset[str]


@cache
def runtime_of(module: ModuleType, taken: frozenset[str]) -> Runtime:
    """The parts of ``module``; ``taken``: names its entry points add (their arguments).
    A helper the runtime imports from the package (`davies_sym.emit.shared_runtime`) is
    copied in, its statements first, and its import is left out: a generated module
    imports nothing of the package."""
    source = inspect.getsource(module)
    lines = source.split("\n")
    tree = ast.parse(source)
    body = tree.body[1:]  # without the docstring
    imports = [n for n in body if isinstance(n, (ast.Import, ast.ImportFrom))]
    helpers = [n for n in imports if isinstance(n, ast.ImportFrom) and (n.module or "").startswith("davies_sym.")]
    own = range(imports[0].lineno - 1, imports[-1].end_lineno or imports[-1].lineno)
    dropped = {k for n in helpers for k in range(n.lineno - 1, n.end_lineno or n.lineno)}
    block = "\n".join(lines[k] for k in own if k not in dropped).strip()
    while "\n\n\n" in block:
        block = block.replace("\n\n\n", "\n\n")
    before: list[str] = []
    after: list[str] = []
    placeholders: dict[str, ast.expr] = {}
    names = {*taken, "float"}  # the builtin the tables use
    imported = {(a.asname or a.name) for n in imports if n not in helpers for a in n.names}
    for imported_from in helpers:
        helper = runtime_of(importlib.import_module(imported_from.module or ""), frozenset())
        needs = {(a.asname or a.name) for n in ast.parse(helper.imports).body for a in getattr(n, "names", [])}
        if helper.placeholders or helper.after or not needs <= imported:
            raise DerivationError(
                f"{imported_from.module} must have no placeholders and only imports {module.__name__} has"
            )
        before += helper.before
        names |= helper.names
    for node in body[len(imports) :]:
        if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            placeholders[node.target.id] = node.annotation
            continue
        segment = ast.get_source_segment(source, node)
        assert segment is not None
        (after if placeholders else before).append(segment)
    names |= module_level_names(tree)
    return Runtime(block, tuple(before), placeholders, tuple(after), frozenset(names))


def module_level_names(tree: ast.Module) -> set[str]:
    """The names ``tree`` binds at module level: a symbol is a keyword argument of a
    generated function, so only these (and the generated functions' own locals) can
    clash with it; the runtime functions' locals live in their own scopes."""
    names: set[str] = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names |= {(a.asname or a.name).split(".")[0] for a in node.names}
        elif isinstance(node, ast.Assign):
            names |= {t.id for target in node.targets for t in ast.walk(target) if isinstance(t, ast.Name)}
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names


def constant(runtime: Runtime, name: str, value: ast.expr) -> ast.AnnAssign:
    """``NAME: <annotation of the placeholder> = value``."""
    return ast.AnnAssign(ast.Name(name, ast.Store()), runtime.placeholders[name], value, simple=1)


#: Why a symbol or a generated function name cannot be a name of a generated module.
NOT_A_PARAMETER = "a Python keyword, a name the module uses, or not an ASCII identifier"
NOT_A_FUNCTION = "not an ASCII identifier, a name the module uses, or two ports or conditions give the same name"


def refused_name(train: Train, kind: str, name: str, why: str, code: str = "module") -> TopologyError:
    """The refusal of a name a generated file cannot hold (``kind``: ``symbol`` or
    ``generated function name``; ``code``: what is generated), at the entry where the file
    writes it: a symbol where it is first written, a function name (made of the ports) at
    the ports."""
    message = f"the {kind} {name!r} cannot be a name in the generated {code} ({why}); rename it in the topology file"
    problem = train.symbol_problem(name, message) if kind == "symbol" else train.problem("ports", message)
    return TopologyError([problem], train.path)


def usable(runtime: Runtime, name: str) -> bool:
    """Whether ``name`` may be written as an identifier of the generated module."""
    return name.isascii() and name.isidentifier() and not keyword.iskeyword(name) and name not in runtime.names


def _fitted(
    expr: sympy.Expr, fresh: Iterator[sympy.Symbol], steps: list[tuple[sympy.Symbol, sympy.Expr]]
) -> sympy.Expr:
    """``expr`` with long parts moved into temporaries (appended to ``steps``) until its
    code is at most `_BUDGET` characters: sums and products in groups of terms,
    other functions argument by argument."""
    if _width(expr) <= _BUDGET or not expr.args:
        return expr
    args = [_fitted(a, fresh, steps) for a in expr.args]
    if expr.is_Add or expr.is_Mul:
        groups: list[list[sympy.Expr]] = [[]]
        for a in args:
            if groups[-1] and _width(expr.func(*groups[-1], a)) > _BUDGET:
                groups.append([])
            groups[-1].append(a)
        parts = []
        for group in groups:
            if len(group) == 1:
                parts.append(group[0])
                continue
            symbol = next(fresh)
            steps.append((symbol, expr.func(*group)))
            parts.append(symbol)
        if len(parts) == len(args):  # no group formed: every argument alone is long
            parts = [_temporary(a, fresh, steps) for a in args]
            if parts == args:  # long atoms (a number of hundreds of digits): nothing to move
                return expr.func(*parts)
        return _fitted(expr.func(*parts), fresh, steps)
    rebuilt = expr.func(*args)
    if _width(rebuilt) <= _BUDGET:
        return rebuilt
    return expr.func(*(_temporary(a, fresh, steps) for a in args))


def _temporary(
    expr: sympy.Expr, fresh: Iterator[sympy.Symbol], steps: list[tuple[sympy.Symbol, sympy.Expr]]
) -> sympy.Expr:
    if expr.is_Atom:
        return expr
    symbol = next(fresh)
    steps.append((symbol, expr))
    return symbol


def _constants_folded(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with every function of numbers alone (``sin(pi/9)``, ``sqrt(2)``) as its
    double: the array API functions take arrays, not the numbers such a call would pass."""

    def constant_call(e: sympy.Basic) -> bool:
        return bool(e.is_number and not e.is_Rational and (e.is_Function or (e.is_Pow and not e.exp.is_Integer)))

    return expr.replace(constant_call, lambda e: sympy.Float(e.evalf(30), 17))


def formula_function(
    name: str, doc: str, exprs: Sequence[sympy.Expr], returns: str = "Array", relation: bool = False
) -> tuple[ast.FunctionDef, tuple[str, ...]]:
    """A function of the symbols of ``exprs`` returning them (one: an array, several: a
    tuple; ``relation``: whether the expression is positive), common subexpressions and
    long parts computed once, each on its own line; also its argument names."""
    args = tuple(sorted({str(s) for e in exprs for s in e.free_symbols}))
    xp = name_node("xp")
    body: list[ast.stmt] = [docstring(doc, "    ")]
    body.append(ast.Assign([ast.Name("xp", ast.Store())], call("_namespace", *(name_node(a) for a in args))))
    body += [ast.Assign([ast.Name(a, ast.Store())], call("_array", name_node(a), xp)) for a in args]
    fresh = sympy.numbered_symbols(_TEMPORARY)
    exprs = [_constants_folded(e) for e in exprs]
    replacements, reduced = sympy.cse(list(exprs), symbols=fresh, order="canonical")
    steps: list[tuple[sympy.Symbol, sympy.Expr]] = []
    for symbol, value in replacements:
        steps.append((symbol, _fitted(value, fresh, steps)))
    results = [_fitted(e, fresh, steps) for e in reduced]
    body += [ast.Assign([ast.Name(str(s), ast.Store())], parsed(v)) for s, v in steps]
    returned: ast.expr
    if relation:
        returned = call("_truth", ast.Compare(parsed(results[0]), [ast.Gt()], [ast.Constant(0)]), xp)
    elif len(results) == 1:
        returned = call("_array", parsed(results[0]), xp)
    else:
        returned = ast.Tuple([call("_array", parsed(r), xp) for r in results], ast.Load())
    body.append(ast.Return(returned))
    params = [ast.arg(a, name_node("ArrayLike")) for a in args]
    return keyword_function(name, params, [None] * len(args), body, ast.parse(returns, mode="eval").body), args


def table(entries: Sequence[tuple[str, str, Sequence[str]]]) -> ast.Dict:
    """``{key: (function, (argument names))}``."""
    return ast.Dict(
        [ast.Constant(k) for k, _, _ in entries],
        [ast.Tuple([name_node(f), literal(tuple(a))], ast.Load()) for _, f, a in entries],
    )


def compiled_module(source: str, name: str) -> ModuleType:
    """A generated module's ``source`` compiled in memory (``name``: the train's)."""
    module = ModuleType("davies_sym_formulas")
    # The name as a file name for tracebacks: escaped, as a NUL in it is no file name.
    label = name.encode("unicode_escape").decode("ascii")
    exec(compile(source, f"<formulas of {label}>", "exec"), module.__dict__)
    return module


@dataclass(frozen=True)
class FormulaTables:
    """The formula functions of a generated module as they are written, each entered in
    the table that names it by key (``_EFFICIENCY``: variant or region -> its function
    and arguments), which the module's runtime reads."""

    tables: dict[str, list[tuple[str, str, Sequence[str]]]]
    functions: list[ast.FunctionDef] = field(default_factory=list)

    @classmethod
    def named(cls, *tables: str) -> FormulaTables:
        """Empty tables of these names, in this order."""
        return cls({name: [] for name in tables})

    def add(
        self, table: str, key: str, name: str, doc: str, exprs: Sequence[sympy.Expr], returns: str = "Array"
    ) -> tuple[str, ...]:
        """The `formula_function` ``name`` of ``exprs``, entered in ``table`` under
        ``key``; its argument names."""
        return self._enter(table, key, name, formula_function(name, doc, exprs, returns))

    def add_relation(self, table: str, key: str, name: str, doc: str, exprs: Sequence[sympy.Expr]) -> tuple[str, ...]:
        """`add` for a relation: the function says whether the expression is positive (an
        array of booleans)."""
        return self._enter(table, key, name, formula_function(name, doc, exprs, "NDArray[np.bool_]", relation=True))

    def _enter(self, table: str, key: str, name: str, made: tuple[ast.FunctionDef, tuple[str, ...]]) -> tuple[str, ...]:
        """The function ``made`` (with its argument names) kept, and entered in ``table``
        under ``key``; its argument names."""
        function, args = made
        self.functions.append(function)
        self.tables[table].append((key, name, args))
        return args


def module_text(
    runtime: Runtime,
    doc: str,
    constants: Sequence[ast.stmt],
    formulas: FormulaTables,
    entries: Sequence[ast.FunctionDef],
    train: Train,
) -> str:
    """A generated module's source, in its order: the docstring, the runtime's imports and
    helpers, the train's constants, the formula functions and their tables, the runtime's
    choice of variant or region, and the entry points.  A formula function whose name the
    runtime takes, or two of one name, is refused at the entry of ``train`` that made it."""
    names = [f.name for f in formulas.functions]
    for f in formulas.functions:
        if not usable(runtime, f.name) or names.count(f.name) > 1:
            raise refused_name(train, "generated function name", f.name, NOT_A_FUNCTION)
    items: list[tuple[int, str | ast.stmt]] = [(0, docstring(doc, "")), (1, runtime.imports)]
    items += [(2 if k else 1, text) for k, text in enumerate(runtime.before)]
    items += [(2 if k == 0 else 0, node) for k, node in enumerate(constants)]
    items += [(2, f) for f in formulas.functions]
    tables = enumerate(formulas.tables.items())
    items += [(2 if k == 0 else 0, constant(runtime, name, table(rows))) for k, (name, rows) in tables]
    items += [(2, text) for text in runtime.after]
    items += [(2, f) for f in entries]
    return module_source(items)
