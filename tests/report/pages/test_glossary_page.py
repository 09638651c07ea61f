"""The glossary page (lunarcap.report.pages.glossary): generated from lunarcap.quantities."""

from lunarcap import quantities as Q
from lunarcap.report.pages import glossary


def test_page_lists_every_quantity_and_passes_its_checks():
    page = glossary.build()
    page.check()
    table = page.items["quantities"].df
    assert list(table.name) == sorted(Q.GLOSSARY)
    assert page.values["n_quantities"] == len(Q.GLOSSARY)


def test_losses_table_tells_the_references_apart():
    t = glossary.losses_table().set_index("name")
    assert "same dynamics" in t.loc["impulsive_limit_mps", "definition"]
    assert "vis-viva" in t.loc["impulsive_delta_v_two_body_mps", "definition"]
    assert t.loc["delta_v_loss_mps", "definition"] != t.loc["loss_vs_paper_impulse_mps",
                                                            "definition"]
    assert (t.unit.loc[["delta_v_loss_mps", "objective_loss_mps"]] == "m/s").all()


def test_composition_rows_resolve():
    for example in glossary.composition_table().example:
        assert Q.is_known(example), example
