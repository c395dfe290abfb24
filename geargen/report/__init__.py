"""Reports: tables, plots (matplotlib, Agg), manufacturing drawings (geargen's own SVG and PDF writer,
:mod:`geargen.report.vector`), JSON, Markdown/HTML."""
