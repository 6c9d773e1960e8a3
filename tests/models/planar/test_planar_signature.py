"""The planar engine is compiled once whatever the entry point (as the rocking
engine): a cold compile costs ~13 s of CPU, so a free-rocking run (a motion without a
vertical component: a fresh writable array of zeros), a record with its vertical and the
batch must hand `models.planar.engine.integrate` arrays of one type."""

import shaketable as st
from shaketable.ground import records
from shaketable.models.planar import engine as planar
from shaketable.models.planar.batch import simulate_many_planar


def test_free_rocking_a_record_and_the_batch_share_one_compiled_signature():
    block = st.Block.parse("30x6in")
    pacoima = records.load("pacoima-dam-s16e")
    st.simulate(block, None, cor=0.9, theta0=0.5 * block.alpha, friction=st.Friction(0.5),
                duration=0.1)
    st.simulate(block, pacoima, cor=0.9, friction=st.Friction(0.5), duration=0.5)
    horizontal_only = st.Motion(t=pacoima.t, horizontal=pacoima.horizontal)
    st.simulate(block, horizontal_only, cor=0.9, friction=st.Friction(0.3), duration=0.5)
    simulate_many_planar([block], pacoima, st.Friction(0.3), [0.9], duration=0.5)
    assert len(planar.integrate.signatures) == 1, planar.integrate.signatures
