"""The book's build system: the pages' notebooks executed by papermill, then the HTML build.

Its Sphinx extensions and the checks of the built book (its words, its screenshots) too.
"""
