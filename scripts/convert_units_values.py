"""The values of scripts/convert-units: its error (ConversionError,
fail()), numbers and lists of numbers rescaled exactly and written as the
shortest text of their double, and the functions of space and time (and
mu(s)): their arguments and components wrapped in (and unwrapped from)
the unit constants. Standard library only.
"""

import re
from fractions import Fraction


# ---------------------------------------------------------------- errors
class ConversionError(Exception):
    pass


def fail(message):
    raise ConversionError(message)


# --------------------------------------------------------------- numbers
NUMBER_RE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


def parse_number(text):
    """The double of @p text (as the program reads it), None if none."""
    text = text.strip()
    if not NUMBER_RE.fullmatch(text):
        return None
    return float(text)


def format_number(x):
    """The shortest text that reads back to the double @p x."""
    r = repr(x)
    if r.endswith(".0"):
        r = r[:-2]
    return r


def scaled(x, factor):
    """The double nearest to x * factor (@p factor exact)."""
    try:
        return float(Fraction(x) * factor)
    except OverflowError:
        return None


def scale_number_text(text, factor, where):
    """@p text (a number, maybe with spaces around) times @p factor."""
    core = text.strip()
    value = parse_number(core)
    if value is None:
        fail("%s'%s' is not a number" % (where, core))
    if value == 0 or factor == 1:
        return text
    result = scaled(value, factor)
    if result is None or result in (float("inf"), float("-inf")):
        fail("%s%s is out of the range of a double after the conversion"
             % (where, core))
    lead = text[:len(text) - len(text.lstrip())]
    trail = text[len(text.rstrip()):]
    return lead + format_number(result) + trail


def scale_list_text(text, factor, where):
    if not text.strip():
        return text
    return ",".join(scale_number_text(item, factor, where)
                    for item in text.split(","))


# ----------------------------------------------------------- expressions
TOKEN_RE = re.compile(r"(?P<ws>\s+)|(?P<num>(?:\d+\.?\d*|\.\d+)"
                      r"(?:[eE][+-]?\d+)?)|(?P<id>[A-Za-z_][A-Za-z0-9_]*)"
                      r"|(?P<op>.)", re.S)


def tokenize(text):
    return [(m.lastgroup, m.group()) for m in TOKEN_RE.finditer(text)]


def identifiers(text):
    return {t for k, t in tokenize(text) if k == "id"}


def parse_constants(text):
    """[(item text, name or None, value text or None)] of Function
    constants (comma separated name=value pairs)."""
    if not text.strip():
        return []
    items = []
    for item in text.split(","):
        parts = item.split("=")
        if len(parts) == 2:
            items.append([item, parts[0].strip(), parts[1].strip()])
        else:
            items.append([item, None, None])
    return items


def join_constants(items):
    texts = [i[0] for i in items]
    if texts:
        texts[0] = texts[0].lstrip()
    return ",".join(texts)


def set_constant(items, name, value):
    """Set the constant @p name of @p items to @p value (None: remove)."""
    for k, item in enumerate(items):
        if item[1] == name:
            if value is None:
                del items[k]
            else:
                lead = item[0][:len(item[0]) - len(item[0].lstrip())]
                item[0] = "%s%s=%s" % (lead, name, value)
                item[2] = value
            return
    if value is not None:
        items.append([("" if not items else " ") + "%s=%s" % (name, value),
                      name, value])


def significant(tokens):
    """Indices of the tokens that are not white space."""
    return [i for i, (k, _) in enumerate(tokens) if k != "ws"]


def wrapped_occurrences(tokens, variables, name):
    """If every occurrence of the variables and of @p name in @p tokens is
    a group '(v*name)', the list of (first, last) token indices of the
    groups; else None."""
    sig = significant(tokens)
    text = [tokens[i][1] for i in sig]
    groups = []
    used = set()
    for j, t in enumerate(text):
        if tokens[sig[j]][0] != "id" or (t not in variables and t != name):
            continue
        if j in used:
            continue
        start = j - 1 if t in variables else j - 3
        if start < 0 or start + 4 >= len(text):
            return None
        if not (text[start] == "(" and text[start + 1] in variables and
                text[start + 2] == "*" and text[start + 3] == name and
                text[start + 4] == ")"):
            return None
        used.update((start + 1, start + 3))
        groups.append((sig[start], sig[start + 4], text[start + 1]))
    return groups


def replace_groups(tokens, groups, make):
    """@p tokens with each group (first, last, variable) replaced by
    make(variable)."""
    out = []
    k = 0
    for first, last, variable in sorted(groups):
        out.extend(t for _, t in tokens[k:first])
        out.append(make(variable))
        k = last + 1
    out.extend(t for _, t in tokens[k:])
    return "".join(out)


def fresh_name(base, taken):
    name, n = base, 1
    while name in taken:
        n += 1
        name = "%s_%d" % (base, n)
    return name


def near_one(x):
    return abs(x - 1) <= 1e-13


def candidates(constants, base):
    """The constants named @p base or @p base_N (as fresh_name() makes
    them), newest first, with their values."""
    found = []
    for item in constants:
        if item[1] is not None and re.fullmatch(re.escape(base) + r"(_\d+)?",
                                                item[1]):
            value = parse_number(item[2])
            if value is not None:
                found.append((item[1], value))
    return found[::-1]


def substitute_arguments(expression, constants, variables, factor, base,
                         taken):
    """f(v) -> f(v*c) for the @p variables, c = @p factor (exact); returns
    the new expression (constants updated in place). Where the variables
    are wrapped already, '(v*name)' for a constant name = base or base_N
    of an earlier conversion, its value is multiplied instead."""
    tokens = tokenize(expression)
    present = [v for v in variables
               if any(k == "id" and t == v for k, t in tokens)]
    if factor == 1 or not present:
        return expression
    for name, old_value in candidates(constants, base):
        groups = wrapped_occurrences(tokens, set(variables), name)
        if groups:
            new_value = scaled(old_value, factor)
            if near_one(new_value):
                set_constant(constants, name, None)
                return replace_groups(tokens, groups, lambda v: v)
            set_constant(constants, name, format_number(new_value))
            return expression
    name = fresh_name(base, taken)
    taken.add(name)
    set_constant(constants, name, format_number(float(factor)))
    return "".join("(%s*%s)" % (t, name) if k == "id" and t in variables
                   else t for k, t in tokens)


def split_component(component):
    core = component.strip()
    lead = component[:len(component) - len(component.lstrip())]
    trail = component[len(component.rstrip()):] if core else ""
    return lead, core, trail


def wrapped_component(core, name):
    """The inner text if @p core is 'name*(inner)', else None."""
    tokens = tokenize(core)
    sig = significant(tokens)
    if len(sig) < 4 or tokens[sig[0]][1] != name or \
            tokens[sig[1]][1] != "*" or tokens[sig[2]][1] != "(" or \
            tokens[sig[-1]][1] != ")":
        return None
    depth = 0
    for j in sig[2:]:
        t = tokens[j][1]
        depth += (t == "(") - (t == ")")
        if depth == 0 and j != sig[-1]:
            return None
    if any(tokens[j][1] == name for j in sig[1:]):
        return None
    return "".join(t for _, t in tokens[sig[2] + 1:sig[-1]])


def scale_result(expression, constants, factor, taken, where):
    """Each component c of @p expression -> unit_result*(c) (a number is
    rescaled); returns the new expression. Where every component is
    'name*(c)' already, name = unit_result or unit_result_N a constant of
    an earlier conversion, its value is multiplied instead."""
    if factor == 1 or not expression.strip():
        return expression
    components = [split_component(c) for c in expression.split(";")]
    others = [c for _, c, _ in components if c and parse_number(c) is None]
    fold = None
    if others:
        for name, old_value in candidates(constants, "unit_result"):
            if all(wrapped_component(c, name) is not None for c in others):
                fold = name
                new_value = scaled(old_value, factor)
                name = None if near_one(new_value) else name
                set_constant(constants, fold, None if name is None else
                             format_number(new_value))
                break
        else:
            name = fresh_name("unit_result", taken)
            taken.add(name)
            set_constant(constants, name, format_number(float(factor)))
    out = []
    for lead, core, trail in components:
        if not core:
            out.append(lead + trail)
        elif parse_number(core) is not None:
            out.append(lead + scale_number_text(core, factor, where) + trail)
        elif fold is not None:
            body = wrapped_component(core, fold)
            out.append(lead + (body if name is None else core) + trail)
        else:
            out.append("%s%s*(%s)%s" % (lead, name, core, trail))
    return ";".join(out)
