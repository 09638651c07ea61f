"""How many capture burns: a plan's capture in N burns, periods optimised."""
