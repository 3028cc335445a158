"""The examples in the package's docstrings run and give what they say."""

import doctest

import holey


def test_docstring_examples():
    result = doctest.testmod(holey, verbose=False)
    assert result.attempted >= 5
    assert result.failed == 0
