#!/usr/bin/python3
"""Writes one sheet of an Excel workbook (.xlsx) as CSV, the form `waam thermal replay` reads (docs/REPLAY.md).

    /usr/bin/python3 tools/xlsx_to_csv.py BOOK.xlsx OUT.csv [--sheet N]

Standard library only (an .xlsx is a zip of XML, ECMA-376 part 1, section 18): no openpyxl or pandas needed.
- Every row of the sheet becomes one CSV line, metadata rows included (the scenario's `replay.header_rows` skips
  them); a missing cell is an empty field; a row missing from the sheet is an empty line.
- Numbers are written as stored (shortest repr); shared and inline strings as text, quoted when they hold a comma,
  a quote or a line end.
- A number in a cell whose format is a time of day (built-in formats 18-21, 45-47, or a custom format with h or s)
  is written as hh:mm:ss[.fff] (a spreadsheet stores a time as a fraction of a day), as the spreadsheet shows it;
  a date-time is written as YYYY-MM-DD hh:mm:ss. Read it with `replay.time_unit: hh:mm:ss`.
Exits 2 with one line on stderr when the file is not a readable workbook or has no such sheet.
"""
import csv
import os
import datetime
import re
import sys
import zipfile
import xml.etree.ElementTree as ET

NS = {"m": "http://schemas.openxmlformats.org/spreadsheetml/2006/main",
      "r": "http://schemas.openxmlformats.org/officeDocument/2006/relationships"}
TIME_BUILTIN = {18, 19, 20, 21, 45, 46, 47}   # h:mm AM/PM, h:mm:ss AM/PM, h:mm, h:mm:ss, mm:ss, [h]:mm:ss, mm:ss.0
DATETIME_BUILTIN = {22}                       # m/d/yy h:mm
DATE_BUILTIN = {14, 15, 16, 17}


def fail(message):
    print(f"xlsx_to_csv: {message}", file=sys.stderr)
    sys.exit(2)


def shared_strings(book):
    if "xl/sharedStrings.xml" not in book.namelist():
        return []
    root = ET.fromstring(book.read("xl/sharedStrings.xml"))
    return ["".join(t.text or "" for t in si.iter(f"{{{NS['m']}}}t")) for si in root.findall("m:si", NS)]


def style_kinds(book):
    """For each cell style index: 'time', 'datetime', 'date' or '' (a plain number)."""
    if "xl/styles.xml" not in book.namelist():
        return []
    root = ET.fromstring(book.read("xl/styles.xml"))
    custom = {}
    for fmt in root.findall("m:numFmts/m:numFmt", NS):
        # Drop quoted literals, escapes and colour/condition brackets, keep elapsed-time brackets like [h].
        code = re.sub(r'"[^"]*"|\\.|\[(?![hms]+\])[^\]]*\]', "", fmt.get("formatCode", "")).lower()
        has_time = "h" in code or "s" in code
        has_date = "d" in code or "y" in code
        custom[int(fmt.get("numFmtId"))] = ("datetime" if has_date else "time") if has_time else (
            "date" if has_date else "")
    kinds = []
    for xf in root.findall("m:cellXfs/m:xf", NS):
        fid = int(xf.get("numFmtId", "0"))
        if fid in custom:
            kinds.append(custom[fid])
        else:
            kinds.append("time" if fid in TIME_BUILTIN else "datetime" if fid in DATETIME_BUILTIN
                         else "date" if fid in DATE_BUILTIN else "")
    return kinds


def sheet_path(book, index):
    """The zip path of the index-th (1-based) sheet in workbook order."""
    wb = ET.fromstring(book.read("xl/workbook.xml"))
    sheets = wb.findall("m:sheets/m:sheet", NS)
    if not 1 <= index <= len(sheets):
        fail(f"the workbook has {len(sheets)} sheet(s); --sheet {index} does not exist")
    rid = sheets[index - 1].get(f"{{{NS['r']}}}id")
    rels = ET.fromstring(book.read("xl/_rels/workbook.xml.rels"))
    for rel in rels:
        if rel.get("Id") == rid:
            target = rel.get("Target").lstrip("/")
            return target if target.startswith("xl/") else "xl/" + target
    fail(f"sheet {index}: no relationship {rid} in xl/_rels/workbook.xml.rels")


def clock(days, with_date):
    """A spreadsheet day number as hh:mm:ss[.fff] (milliseconds rounded), with the date when asked."""
    ms = round(days * 86400000.0)
    day, ms = divmod(ms, 86400000)
    h, rest = divmod(ms, 3600000)
    m, rest = divmod(rest, 60000)
    s, ms = divmod(rest, 1000)
    text = f"{h:02d}:{m:02d}:{s:02d}" + (f".{ms:03d}" if ms else "")
    if with_date:
        text = (datetime.date(1899, 12, 30) + datetime.timedelta(days=day)).isoformat() + " " + text
    return text


def column_index(ref):
    letters = re.match(r"[A-Z]+", ref).group(0)
    n = 0
    for ch in letters:
        n = n * 26 + ord(ch) - 64
    return n - 1


def cell_text(c, strings, kinds):
    kind = c.get("t", "n")
    if kind == "inlineStr":
        return "".join(t.text or "" for t in c.iter(f"{{{NS['m']}}}t"))
    v = c.find("m:v", NS)
    if v is None or v.text is None:
        return ""
    if kind == "s":
        return strings[int(v.text)]
    if kind in ("str", "e"):
        return v.text
    if kind == "b":
        return v.text
    style = int(c.get("s", "0"))
    fmt = kinds[style] if style < len(kinds) else ""
    number = float(v.text)
    if fmt == "time":
        return clock(number, with_date=number >= 1.0)
    if fmt == "datetime":
        return clock(number, with_date=True)
    if fmt == "date":
        return (datetime.date(1899, 12, 30) + datetime.timedelta(days=int(number))).isoformat()
    return repr(number) if not number.is_integer() else str(int(number))


def main(argv):
    args = [a for a in argv if not a.startswith("--sheet")]
    sheet = 1
    for i, a in enumerate(argv):
        if a == "--sheet" and i + 1 < len(argv):
            sheet = int(argv[i + 1])
            args.remove(argv[i + 1])
    if len(args) != 2:
        fail("usage: xlsx_to_csv.py BOOK.xlsx OUT.csv [--sheet N]")
    source, target = args
    try:
        book = zipfile.ZipFile(source)
        strings, kinds = shared_strings(book), style_kinds(book)
        root = ET.fromstring(book.read(sheet_path(book, sheet)))
    except (OSError, zipfile.BadZipFile, KeyError, ET.ParseError) as e:
        fail(f"{source}: not a readable .xlsx workbook ({e})")
    rows, last = [], 0
    for row in root.findall("m:sheetData/m:row", NS):
        r = int(row.get("r", last + 1))
        rows.extend([[]] * (r - last - 1))
        cells = []
        for c in row.findall("m:c", NS):
            col = column_index(c.get("r")) if c.get("r") else len(cells)
            cells.extend([""] * (col - len(cells)))
            cells.append(cell_text(c, strings, kinds))
        rows.append(cells)
        last = r
    tmp = target + ".tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as out:
        csv.writer(out, lineterminator="\n").writerows(rows)
    os.replace(tmp, target)
    print(f"{target}: {len(rows)} rows from sheet {sheet} of {source}", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
