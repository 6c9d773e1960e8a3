"""The gallery scripts, installed as package data (``shaketable examples --out DIR``)."""
