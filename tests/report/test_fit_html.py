"""The fit report as HTML: the Markdown's blocks rendered by the build report's one HTML writer,
the figures linked as the PNG files beside the page."""

import re

from geargen.report.review import from_markdown, to_html

TEXT = """# Fit report: run 3

*a bench run*

Kind `preload_trace`, **4096** samples.

## Result

| stage | rms | note |
|---|---|---|
| declared | 2.91 | a \\| b |
| extended | 0.50 | plain |

- first note
- second note

```
raw | text
```

![Data and model](fit_data.png)
"""


def test_markdown_blocks_become_the_review_blocks():
    review = from_markdown(TEXT, "explained")
    assert review.title == "Fit report: run 3"
    kinds = [k for k, _ in review.blocks]
    assert kinds == ["p", "p", "h2", "table", "list", "pre", "figure"]
    header, rows = review.blocks[3][1]
    assert header == ["stage", "rms", "note"]
    assert rows == [["declared", "2.91", "a | b"], ["extended", "0.50", "plain"]]
    assert review.blocks[1][1] == "Kind preload_trace, 4096 samples."
    assert review.blocks[4][1] == ["first note", "second note"]
    assert review.blocks[5][1] == "raw | text"
    assert review.blocks[6][1] == ("Data and model", "fit_data.png")


def test_the_page_links_its_figures_as_files():
    page = to_html(from_markdown(TEXT, "explained"))
    assert "<img alt='Data and model' src='fit_data.png'>" in page
    assert "base64" not in page
    assert len(re.findall("<td>", page)) == 6 and "<td>a | b</td>" in page
