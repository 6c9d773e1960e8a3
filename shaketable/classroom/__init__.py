"""The classroom page: a block on a shaking table in the browser, recomputed as the inputs move.

Two parts: :mod:`shaketable.classroom.model` turns the page's fields (text with units, as a
teacher types them) into a scene, runs it with the scene pipeline and returns what the page
draws (plain functions, no browser and no web library); :mod:`shaketable.classroom.page`
builds the page with Panel (on Bokeh) and serves it on this machine
(``shaketable classroom``). Panel is an optional extra (``pip install shaketable[classroom]``)
loaded only by the page.
"""
