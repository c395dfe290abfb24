"""Reports: tables, plots (matplotlib, Agg), JSON, Markdown/HTML."""
