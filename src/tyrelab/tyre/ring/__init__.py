"""The flexible ring tyre model (FTire class): belt segments, tread blocks."""
