"""Report: figure data, figures, tables for the book, provenance and the book build."""
