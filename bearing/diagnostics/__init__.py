"""Diagnostics of axle-box signals: telling a real bearing fault from a coaxial pseudo-fault.

One channel:

* :mod:`.indicators` RMS, peak, kurtosis, crest factor;
* :mod:`.spectral` frequency centre FC and frequency variance VF on the Welch PSD (paper Eq. 18);
* :mod:`.envelope` Hilbert envelope, envelope spectrum, band choice by spectral kurtosis;
* :mod:`.faultlines` BPFO/BPFI/FTF lines and harmonics against the local noise floor;
* :mod:`.spm` shock value from the EMD IMFs and the SPM level (paper Eq. 17) with its bands;
* :mod:`.channel` all of the above on one channel (:func:`.channel.analyse`).

Two channels: :mod:`.lag` time lag, :mod:`.criterion` the paper's criterion, :mod:`.pair`
both sides of one wheelset.

While the speed changes: :mod:`.ordertrack` and :mod:`.clock` the record on the shaft's angle,
:mod:`.ias` the shaft's speed read from the record itself (no tacho).

Nothing heavy is imported here; import the module you need.
"""
