"""How much of a generated function could run two-wide: its statements paired by shape.

    cargo run --release -p dynamics-codegen -- FILE.rs --whole > generated.rs
    python3 models/tools/pairing_potential.py generated.rs FUNCTION

Reads FUNCTION's kernel from the command-line compiler's output (`let vN = ...;`
statements and the `(*out)[i][j] = vN;` stores of an `_into` function) and pairs its
operations greedily, from the stores down: two operations pair when their expression trees
have the same shape (the same operations in the same places; constants, inputs and the
sines and cosines are leaves, whatever their values). Two matchings: `exact` (an addition
pairs with an addition, a fused a·b + c with the same signs only), and `signs ignored`
(additions with subtractions, fused products whatever their signs: a pair that mixes them
would need negated constants or an extra instruction). For each it prints the operations
paired (each pair one two-wide instruction instead of two), the operands that would have
to be packed into a pair because they are not the result of one (constants and input pairs,
which cost a constant load, and computed values, which cost a shuffle), and the paired
results that an unpaired operation or a store reads (a shuffle for the high half).

Written for the g1 humanoid's mass matrix, whose two legs and two arms are mirror images
(BENCHMARKS.md, "M on the humanoid"): a measurement, not part of the product.
"""

import collections
import re
import sys


def kernel(text, function):
    start = text.index(f"fn {function}<")
    end = text.find("\n    pub fn ", start + 1)
    return text[start : end if end > 0 else len(text)]


def parse(src):
    leaves, nodes = {}, {}
    trig = re.search(r"let \(\s*\[([^\]]*)\],\s*\[([^\]]*)\],?\s*\) = T::sin_cos_array", src)
    if trig:
        for group in trig.groups():
            for name in re.findall(r"v\d+", group):
                leaves[name] = "input"
    for statement in re.finditer(r"let (v\d+) = ([^;]*);", src):
        name, e = statement.group(1), statement.group(2).strip()
        fused = re.fullmatch(r"isa\.mul_add\((-?)(v\d+), (-?)(v\d+), (-?)(v\d+)\)", e)
        binary = re.fullmatch(r"(v\d+) ([-+*]) (v\d+)", e)
        negation = re.fullmatch(r"-(v\d+)", e)
        if e.startswith("T::from_f64"):
            leaves[name] = "constant"
        elif re.fullmatch(r"q\[\d+\]", e):
            leaves[name] = "input"
        elif fused:
            signs = "".join("n" if fused.group(k) else "p" for k in (1, 3, 5))
            nodes[name] = ("fma" + signs, [fused.group(k) for k in (2, 4, 6)])
        elif binary:
            nodes[name] = (binary.group(2), [binary.group(1), binary.group(3)])
        elif negation:
            nodes[name] = ("neg", [negation.group(1)])
        else:
            sys.exit(f"unparsed statement: let {name} = {e};")
    stores = re.findall(r"\(\*out\)\[\d+\]\[\d+\] = (v\d+);", src)
    return leaves, nodes, stores


def pairing(leaves, nodes, stores, ignore_signs):
    def kind(op):
        if ignore_signs and op.startswith("fma"):
            return "fma"
        if ignore_signs and op in "+-":
            return "add"
        return op

    shape = {}

    def shape_of(n):
        if n in leaves:
            return "leaf"
        if n not in shape:
            op, children = nodes[n]
            parts = [shape_of(c) for c in children]
            if kind(op) in ("+", "*", "add"):
                parts = sorted(parts, key=str)
            shape[n] = hash((kind(op), tuple(parts)))
        return shape[n]

    for n in sorted(nodes, key=lambda n: int(n[1:])):
        shape_of(n)
    same_shape = collections.defaultdict(list)
    for n in nodes:
        same_shape[shape[n]].append(n)
    partner = {}

    def pair(a, b):
        work = [(a, b)]
        while work:
            a, b = work.pop()
            if a == b or a in leaves or b in leaves or a in partner or b in partner:
                continue
            if shape[a] != shape[b]:
                continue
            partner[a], partner[b] = b, a
            (op, ca), (_, cb) = nodes[a], nodes[b]
            if kind(op) in ("+", "*", "add") and shape_of(ca[0]) != shape_of(cb[0]):
                cb = [cb[1], cb[0]]
            work.extend(zip(ca, cb))

    for n in sorted(nodes, key=lambda n: -int(n[1:])):
        if n not in partner:
            for m in same_shape[shape[n]]:
                if m != n and m not in partner:
                    pair(n, m)
                    break
    packs = collections.Counter()
    for a, b in partner.items():
        if int(a[1:]) < int(b[1:]):
            for x, y in zip(nodes[a][1], nodes[b][1]):
                if partner.get(x) != y and x != y:
                    packs["leaves" if x in leaves and y in leaves else "computed"] += 1
    users = collections.defaultdict(list)
    for n, (_, children) in nodes.items():
        for c in children:
            users[c].append(n)
    stored = set(stores)
    unpacks = sum(
        1 for a in partner if a in stored or any(u not in partner for u in users[a])
    )
    return len(partner), packs, unpacks


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src = kernel(open(sys.argv[1]).read(), sys.argv[2])
    leaves, nodes, stores = parse(src)
    print(f"{sys.argv[2]}: {len(nodes)} operations (a fused a·b + c counts one)")
    for label, ignore in (("exact", False), ("signs ignored", True)):
        paired, packs, unpacks = pairing(leaves, nodes, stores, ignore)
        print(
            f"  {label}: {paired} operations paired ({100 * paired / len(nodes):.0f} %, "
            f"{paired // 2} two-wide instructions saving as many), operands to pack: "
            f"{packs['leaves']} from constants and inputs, {packs['computed']} computed; "
            f"paired results read alone or stored: {unpacks}"
        )


if __name__ == "__main__":
    main()
