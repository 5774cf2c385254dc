#!/usr/bin/env python3
"""The rule coverage of the conformance suite: which vectors exercise each rule.

Each normative rule of spec/ carries a tag such as [R5.3-2] (clause 5.3, rule 2),
written after the rule in its check table or sentence. Each vector of
manifest.json lists the tags it exercises in "rules". This script

  - finds every rule-bearing unit of the normative text (a paragraph, list item or
    table row with MUST, SHALL or REQUIRED, a row of a check table with a Code
    column, or a sentence that names a status code with "otherwise", "error" or in
    parentheses) and requires a tag in it;
  - requires a vector for every tag, except the few in NOT_BY_VECTORS, which say
    why no stream can test them and what tests them instead;
  - requires every tag a vector names to exist in the text;
  - reports a chapter with rule-bearing units but no tag at all by name: a
    chapter is not covered until its rules are tagged;
  - writes coverage.md, the table of rules and their vectors.

  python3 conformance/coverage.py          write coverage.md, then check
  python3 conformance/coverage.py --check  fail if coverage.md is stale or a rule has no vector
"""
import argparse
import glob
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SPEC = os.path.join(HERE, "..", "spec")

TAG = re.compile(r"\[R([0-9AB][0-9.]*)-(\d+)\]")
MUST = re.compile(r"\b(MUST|SHALL|REQUIRED)\b")
CODE_MENTION = re.compile(r"(\(|otherwise |error |rejected with |stop with )(10[1-5]|11\d|130|20[1-8]|30[1-4]|904)\b")

# Tags no conformance vector can exercise, and what covers them instead.
NOT_BY_VECTORS = {
    "R1.6-4": "a rule for encoders: the reference encoder's unit tests decode what it writes",
    "R1.6-5": "robustness on any input: the fuzz targets (fuzz/) and their corpus replays",
    "R2.2.1-2": "applies from version 1.0 on; every draft version is its own format",
    "R2.3-6": "a vector would be 12 MB of empty chunks: ContainerReader.TooManyChunks builds it in memory",
    "R4.3-2": "implied by 3.1: an axis of at most 2^24 samples has size(0) below 2^24 + 2^16 + 3",
    "R2.6-11": "a rule for encoders: the encoder refuses such metadata with 903 (unit tests)",
    "R6.7.2-5": "implied by R6.7.2-1 to R6.7.2-4: no coded values pass those and give an invalid split",
    "R7.1-6": "a decoder of the tet profile alone meeting GHDR or PHDR: every decoder the suite runs implements "
              "the profiles it is given (run_conformance.py --profile); the reference tests build it in memory",
    "R7.6.1-1": "a rotation never fails in a sphere or disk: in TBAS rule 6 of 7.4 reports it (R7.4-6, "
                "pt_base_duplicate_tet), and every level a split reaches is one (7.3)",
    "R7.6.3-1": "never fails for a cut 7.7.2 decodes in a sphere or disk (7.6.3): no coded values reach it",
    "R7.6.3-2": "never fails for a cut 7.7.2 decodes in a sphere or disk (7.6.3): no coded values reach it",
    "RA.3-1": "robustness on any input: the fuzz targets (fuzz/) and their corpus replays",
    "RA.3-2": "allocation before checks: the fuzz targets under AddressSanitizer, with small memory limits",
    "RB.4-1": "allocation before checks: the fuzz targets under AddressSanitizer, with small memory limits",
    "RB.4-2": "overflow of products: UndefinedBehaviorSanitizer in CI, and too_many_samples_3d",
}

# Chapters whose rules are being written and not tagged yet, e.g. {"7"}: reported
# as a NOTE instead of failing. Empty: every chapter with rules must be tagged.
PENDING = set()


def chapter_of(path):
    name = os.path.basename(path)
    m = re.match(r"(\d+)-", name)
    if m:
        return str(int(m.group(1)))
    m = re.match(r"annex-([a-z])-", name)
    return "Annex " + m.group(1).upper() if m else name


def units(path):
    """(line number, text, kind, informative, table has a Code column) of each unit."""
    lines = open(path, encoding="utf-8").read().split("\n")
    out = []
    informative_level = None
    in_code = False
    header_cols = None
    current, start, kind = [], 0, None

    def flush():
        nonlocal current, kind
        if current:
            out.append((start, " ".join(current), kind, informative_level is not None, False))
        current, kind = [], None

    for n, line in enumerate(lines, 1):
        if line.startswith("```"):
            flush()
            in_code = not in_code
            continue
        if in_code:
            continue
        m = re.match(r"(#+) ", line)
        if m:
            flush()
            level = len(m.group(1))
            if informative_level is not None and level <= informative_level:
                informative_level = None
            if "(informative" in line.lower() and informative_level is None:
                informative_level = level
            continue
        if line.startswith("|"):
            flush()
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if header_cols is None:
                header_cols = cells
            elif not set(line) <= set("|-: "):
                out.append((n, line, "row", informative_level is not None, "Code" in header_cols))
            continue
        header_cols = None
        if not line.strip():
            flush()
            continue
        if re.match(r"\s*(- |\d+\. )", line):
            flush()
            start, kind = n, "item"
            current = [line.strip()]
            continue
        if not current:
            start, kind = n, "para"
        current.append(line.strip())
    flush()
    return out


def scan():
    """Tags defined in the text, units that need a tag but have none, per-chapter counts."""
    rules, untagged, chapters = {}, [], {}
    files = sorted(glob.glob(os.path.join(SPEC, "[0-9][0-9]-*.md"))) + \
        sorted(glob.glob(os.path.join(SPEC, "annex-*.md")))
    for path in files:
        chapter = chapter_of(path)
        stats = chapters.setdefault(chapter, {"rules": 0, "tags": 0, "file": os.path.basename(path)})
        section = ""
        for n, text, kind, informative, coded_table in units(path):
            tags = ["R%s-%s" % m for m in TAG.findall(text)]
            # Annex A.1 lists the codes and Annex B tabulates limits with the clause of each rule.
            listing = chapter in ("Annex A", "Annex B") and kind == "row"
            plain = TAG.sub("", text)
            words = re.sub(r"`[^`]*`", "", plain)  # names and examples in code font are not rules
            informative = informative or plain.lstrip("|- ").startswith("*(Informative")
            needs = not informative and not listing and (
                MUST.search(words) or (kind == "row" and coded_table) or CODE_MENTION.search(words))
            if needs:
                stats["rules"] += 1
                if not tags:
                    untagged.append((os.path.basename(path), n, plain.strip()[:110]))
            for tag in tags:
                stats["tags"] += 1
                if tag not in rules:
                    clause = tag[1:].rsplit("-", 1)[0]
                    summary = sentence_of(text, "[%s]" % tag)
                    rules[tag] = {"clause": clause, "text": summary, "file": os.path.basename(path), "line": n}
    return rules, untagged, chapters


def sentence_of(text, tag):
    """The sentence (or table cell) of `text` that ends at `tag`, without tags."""
    end = text.index(tag)
    start = max(text.rfind(". ", 0, end) + 2, text.rfind("|", 0, end) + 1, text.rfind("; ", 0, end) + 2, 0)
    sentence = TAG.sub("", text[start:end])
    return re.sub(r"\s+", " ", re.sub(r"^\s*(- |\d+\. )", "", sentence)).strip()


def sort_key(tag):
    clause, number = tag[1:].rsplit("-", 1)
    parts = [(0, int(p)) if p.isdigit() else (1, p) for p in clause.split(".")]
    return (parts, int(number))


def render(rules, vectors_of):
    lines = ["# Rule coverage of the conformance suite", "",
             "Generated by `conformance/coverage.py` from the rule tags of `spec/` and the `rules` of",
             "`manifest.json`; do not edit. Each rule of the text is listed with the vectors that",
             "exercise it, or with the reason no stream can (`NOT_BY_VECTORS` in the script).", "",
             "| Rule | Clause | Rule text | Vectors |", "|---|---|---|---|"]
    for tag in sorted(rules, key=sort_key):
        r = rules[tag]
        text = r["text"].replace("|", "/")
        if len(text) > 140:
            text = text[:137] + "..."
        names = vectors_of.get(tag, [])
        cell = ", ".join("`%s`" % n for n in names) if names else "*(none: %s)*" % NOT_BY_VECTORS.get(tag, "MISSING")
        lines.append(f"| {tag} | {r['clause']} | {text} | {cell} |")
    covered = sum(1 for t in rules if vectors_of.get(t))
    lines += ["", f"{len(rules)} rules; {covered} exercised by vectors, {len(rules) - covered} not by vectors "
              "(reason given)."]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="do not write coverage.md; fail if it is stale")
    args = parser.parse_args()
    rules, untagged, chapters = scan()
    with open(os.path.join(HERE, "manifest.json"), encoding="utf-8") as f:
        manifest = json.load(f)
    vectors_of, problems = {}, []
    for v in manifest["vectors"]:
        name = os.path.splitext(os.path.basename(v["file"]))[0]
        if not v.get("rules"):
            problems.append(f"vector {v['file']} lists no rules")
        for tag in v.get("rules", []):
            if tag not in rules:
                problems.append(f"vector {v['file']} names {tag}, which the text does not define")
            vectors_of.setdefault(tag, []).append(name)
    for chapter, stats in sorted(chapters.items()):
        if stats["rules"] and not stats["tags"]:
            message = (f"chapter {chapter} ({stats['file']}): {stats['rules']} MUST or error sentences "
                       "and no rule tags yet: tag its rules and give each a vector (spec/README.md)")
            if chapter in PENDING:
                print("coverage: NOTE " + message)
            else:
                problems.append(message)
    # A chapter without any tag is reported once, above, not sentence by sentence.
    untagged_files = {s["file"] for c, s in chapters.items() if c in PENDING or (s["rules"] and not s["tags"])}
    for file, line, text in untagged:
        if file not in untagged_files:
            problems.append(f"{file}:{line}: a rule without a tag: {text}")
    for tag in sorted(rules, key=sort_key):
        if not vectors_of.get(tag) and tag not in NOT_BY_VECTORS:
            problems.append(f"{tag} ({rules[tag]['file']}:{rules[tag]['line']}) has no vector: {rules[tag]['text'][:90]}")
    for tag in NOT_BY_VECTORS:
        if tag not in rules:
            problems.append(f"NOT_BY_VECTORS names {tag}, which the text does not define")
    table = render(rules, vectors_of)
    path = os.path.join(HERE, "coverage.md")
    if args.check:
        if not os.path.exists(path) or open(path, encoding="utf-8").read() != table:
            problems.append("coverage.md is stale: run conformance/coverage.py")
    else:
        with open(path, "w", encoding="utf-8") as f:
            f.write(table)
    for p in problems:
        print("coverage: " + p)
    covered = sum(1 for t in rules if vectors_of.get(t))
    print(f"coverage: {len(rules)} rules, {covered} with vectors, "
          f"{len([t for t in rules if t in NOT_BY_VECTORS])} not testable by vectors; "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
