"""Readers of accelerogram files: PEER AT2, delimited text, and whatever ObsPy reads
(the only place the package imports ObsPy). Each returns a :class:`~shaketable.ground.readers.common.Record`.
"""
