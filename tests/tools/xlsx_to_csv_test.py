#!/usr/bin/python3
"""tools/xlsx_to_csv.py on a workbook written here (the shape of a cell's log export: metadata rows, a line of names,
times of day in a time format, numbers, a missing cell, an inline string); standard library only."""
import csv
import os
import subprocess
import sys
import tempfile
import unittest
import zipfile

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "xlsx_to_csv.py")
M = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
R = "http://schemas.openxmlformats.org/officeDocument/2006/relationships"


def write_book(path):
    strings = ["Project: test", "Timestamp", "Weld On", "T, inner"]
    sst = "".join(f"<si><t>{s}</t></si>" for s in strings)
    rows = [
        '<row r="1"><c r="A1" t="s"><v>0</v></c></row>',
        # row 2 missing: an empty line
        '<row r="3"><c r="A3" t="s"><v>1</v></c><c r="B3" t="s"><v>2</v></c><c r="C3" t="s"><v>3</v></c></row>',
        # 12:12:08 as a fraction of a day in style 1 (built-in format 21, h:mm:ss); C4 missing
        '<row r="4"><c r="A4" s="1"><v>0.50842592592592595</v></c><c r="B4"><v>1</v></c></row>',
        # 23:59:59.5 in a custom time format (style 2), a date-time serial in style 3, an inline string
        '<row r="5"><c r="A5" s="2"><v>0.99999421296296296</v></c><c r="B5"><v>0</v></c>'
        '<c r="C5" t="inlineStr"><is><t>26.5</t></is></c><c r="D5" s="3"><v>45413.5</v></c></row>',
    ]
    sheet = f'<worksheet xmlns="{M}"><sheetData>{"".join(rows)}</sheetData></worksheet>'
    styles = (f'<styleSheet xmlns="{M}"><numFmts count="1"><numFmt numFmtId="164" formatCode="[h]:mm:ss.0"/>'
              '</numFmts><cellXfs count="4"><xf numFmtId="0"/><xf numFmtId="21"/><xf numFmtId="164"/>'
              '<xf numFmtId="22"/></cellXfs></styleSheet>')
    workbook = (f'<workbook xmlns="{M}" xmlns:r="{R}"><sheets><sheet name="log" sheetId="1" r:id="rId1"/>'
                '</sheets></workbook>')
    rels = ('<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
            '<Relationship Id="rId1" Target="worksheets/sheet1.xml" '
            'Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/worksheet"/></Relationships>')
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("xl/workbook.xml", workbook)
        z.writestr("xl/_rels/workbook.xml.rels", rels)
        z.writestr("xl/worksheets/sheet1.xml", sheet)
        z.writestr("xl/sharedStrings.xml", f'<sst xmlns="{M}">{sst}</sst>')
        z.writestr("xl/styles.xml", styles)


class XlsxToCsv(unittest.TestCase):
    def run_tool(self, *args):
        return subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True)

    def test_rows_times_and_strings(self):
        with tempfile.TemporaryDirectory() as d:
            book, out = os.path.join(d, "log.xlsx"), os.path.join(d, "log.csv")
            write_book(book)
            r = self.run_tool(book, out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out, newline="") as f:
                text = f.read()
            rows = list(csv.reader(text.splitlines()))
            self.assertEqual(rows[0], ["Project: test"])
            self.assertEqual(rows[1], [], "a row missing from the sheet is an empty line")
            self.assertEqual(rows[2], ["Timestamp", "Weld On", "T, inner"])
            self.assertEqual(rows[3], ["12:12:08", "1"], "a time-formatted number is a clock time")
            self.assertEqual(rows[4], ["23:59:59.500", "0", "26.5", "2024-05-01 12:00:00"])
            self.assertIn('"T, inner"', text.splitlines()[2], "a comma in a cell is quoted")

    def test_refuses_what_is_not_a_workbook(self):
        with tempfile.TemporaryDirectory() as d:
            bad = os.path.join(d, "bad.xlsx")
            with open(bad, "w") as f:
                f.write("not a zip")
            r = self.run_tool(bad, os.path.join(d, "out.csv"))
            self.assertEqual(r.returncode, 2)
            self.assertIn("not a readable .xlsx workbook", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(d, "out.csv")), "nothing written")
            book = os.path.join(d, "log.xlsx")
            write_book(book)
            r = self.run_tool(book, os.path.join(d, "out.csv"), "--sheet", "2")
            self.assertEqual(r.returncode, 2)
            self.assertIn("1 sheet(s); --sheet 2", r.stderr)


if __name__ == "__main__":
    unittest.main()
