// The clinician view (route `#/clinician`): choose a target (a saved pose today, phoneme targets
// later: see targets.js) and a client's EPG recording, step through the frames or play them at the
// recording's own frame rate, and read the synthetic and the real palatograms side by side, their
// electrode-by-electrode agreement, the EPG indices of the frame and their curves over time.
//
// Deep links: #/clinician?recording=12&target=pose:3&frame=40. Keys: left and right arrows step,
// Home and End jump, space plays and pauses.

import { fetchJson } from '../api.js';
import { registerDebug } from '../debug.js';
import { EPG_CELLS } from '../core/constants.js';
import { contactRows } from '../core/epgContacts.js';
import { h } from './Controls.js';
import { alignTarget, codesFromRows, frameAtElapsed, framesFromRows, indexTracks } from './clinicianFrames.js';
import { IndexPlot } from './IndexPlot.js';
import { PALATOGRAM_COLORS, Palatogram } from './Palatogram.js';
import { PalatogramStrip } from './PalatogramStrip.js';
import { parseTargetName, postJson, targetSources } from './targets.js';
import { TargetPalate3D } from './TargetPalate3D.js';
import './epg.css';

const SPEEDS = Object.freeze( [ 1, 0.5, 0.25, 0.1 ] );
const TABLE_INDICES = Object.freeze( [ 'percent', 'cog', 'anteriority', 'centrality', 'dorsopalatal', 'alveolar_percent', 'palatal_percent', 'velar_percent' ] );
const GRID = Object.freeze( { rows: 8, columns: 8 } );
const TRACK_COLORS = Object.freeze( { recording: '#1f2328', target: '#b4384a' } );

export class ClinicianView {

	constructor( { fetchImpl = globalThis.fetch, win = globalThis.window } = {} ) {

		this.fetchImpl = fetchImpl;
		this.window = win;
		this.sources = targetSources( { fetchImpl } );
		this.state = { loaded: false, error: null, frame: 0, playing: false, speed: 1, target: null, recording: null, comparison: null, target3d: null };
		this.unregister = [];
		this.loadVersion = 0;

	}

	mount( container ) {

		const option = ( value, label ) => h( 'option', { value }, label );
		this.targetSelect = h( 'select', { 'aria-label': 'Target', onChange: () => this.chooseTarget( this.targetSelect.value ) }, option( '', 'No target' ) );
		this.recordingSelect = h( 'select', { 'aria-label': 'Recording', onChange: () => this.chooseRecording( this.recordingSelect.value ) }, option( '', 'No recording' ) );
		this.speedSelect = h( 'select', { 'aria-label': 'Playback speed', onChange: () => ( this.state.speed = Number( this.speedSelect.value ) ) },
			...SPEEDS.map( ( s ) => option( String( s ), s === 1 ? 'Real time' : `${ s } x (slower)` ) ) );
		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' }, 'Loading targets and recordings…' );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
		const swatch = ( color, outline ) => h( 'span', { className: 'cv-swatch', style: outline ? `border: 2px solid ${ color }` : `background: ${ color }` } );
		const legend = h( 'div', { className: 'cv-legend' },
			h( 'span', {}, swatch( PALATOGRAM_COLORS.contact ), 'contact (agreement: both)' ),
			h( 'span', {}, swatch( PALATOGRAM_COLORS.onlyRecording ), 'recording only' ),
			h( 'span', {}, swatch( PALATOGRAM_COLORS.onlyReference, true ), 'target only' ),
			h( 'span', {}, 'dot: no contact; front (R1) at the top' ) );
		const side = h( 'aside', { className: 'cv-side', 'aria-label': 'Choices' },
			h( 'h1', { className: 'cv-title' }, 'Clinician' ),
			h( 'label', {}, 'Target', this.targetSelect ),
			h( 'label', {}, 'Recording', this.recordingSelect ),
			h( 'label', {}, 'Playback', this.speedSelect ),
			legend, this.status, this.error );

		const button = ( label, text, onClick ) => h( 'button', { type: 'button', 'aria-label': label, title: label, onClick }, text );
		this.playButton = button( 'Play', 'Play', () => this.togglePlay() );
		this.slider = h( 'input', { type: 'range', className: 'cv-slider', min: '0', max: '0', value: '0', 'aria-label': 'Frame', onInput: () => this.setFrame( Number( this.slider.value ) ) } );
		this.frameLabel = h( 'span', { className: 'cv-frame', 'aria-live': 'off' }, '' );
		const transport = h( 'div', { className: 'cv-transport', role: 'group', 'aria-label': 'Frames' },
			button( 'First frame', '|◀', () => this.setFrame( 0 ) ),
			button( 'Previous frame', '◀', () => this.step( - 1 ) ),
			this.playButton,
			button( 'Next frame', '▶', () => this.step( 1 ) ),
			button( 'Last frame', '▶|', () => this.setFrame( this.frameCount() - 1 ) ),
			this.frameLabel );

		const size = { width: 176, height: 196 };
		this.targetPalatogram = new Palatogram( { ...size, ariaLabel: 'Target palatogram (synthetic)' } );
		this.recordingPalatogram = new Palatogram( { ...size, ariaLabel: 'Recording palatogram (real)' } );
		this.agreementPalatogram = new Palatogram( { ...size, ariaLabel: 'Agreement, electrode by electrode' } );
		this.targetCaption = h( 'span', { className: 'cv-sub' }, 'none chosen' );
		this.recordingCaption = h( 'span', { className: 'cv-sub' }, 'none chosen' );
		this.agreementCaption = h( 'span', { className: 'cv-sub' }, 'choose both' );
		const card = ( title, caption, palatogram ) => h( 'figure', { className: 'cv-card cv-narrow' }, h( 'figcaption', {}, title, caption ), palatogram.element );
		this.table = h( 'table', { className: 'cv-table', 'aria-label': 'EPG indices of this frame' } );
		this.stage3d = h( 'div', { className: 'cv-stage3d', role: 'img', 'aria-label': 'The target on the 3D palate: electrodes as dots, contacted ones as squares' } );
		this.caption3d = h( 'figcaption', {}, 'Target on the palate' );
		const pair = h( 'div', { className: 'cv-pair' },
			h( 'figure', { className: 'cv-card cv-wide' }, this.caption3d, this.stage3d ),
			card( 'Target (synthetic)', this.targetCaption, this.targetPalatogram ),
			card( 'Recording (real)', this.recordingCaption, this.recordingPalatogram ),
			card( 'Agreement', this.agreementCaption, this.agreementPalatogram ) );
		this.plot = new IndexPlot( { width: 640, height: 270 } );
		this.strip = new PalatogramStrip( { width: 760, height: 92, onSelect: ( i ) => this.setFrame( i ) } );
		this.stripCaption = h( 'figcaption', {}, 'Over time (click a frame)' );
		this.plotCard = h( 'figure', { className: 'cv-card cv-grow' }, h( 'figcaption', {}, 'Indices over time: recording solid, target dashed' ), this.plot.element );
		const curves = h( 'div', { className: 'cv-pair' },
			h( 'figure', { className: 'cv-card' }, h( 'figcaption', {}, 'Indices of this frame' ), this.table ),
			this.plotCard );
		this.stripCard = h( 'figure', { className: 'cv-card' }, this.stripCaption, this.strip.element );
		this.main = h( 'section', { className: 'cv-main', 'aria-label': 'Frames' }, transport, this.slider, pair, curves, this.stripCard );
		this.root = h( 'div', { className: 'clinician', tabindex: '-1' }, side, this.main );
		container.append( this.root );

		this.onKey = ( event ) => this.key( event );
		this.window.addEventListener( 'keydown', this.onKey );
		this.resizeObserver = new ResizeObserver( () => this.fit() );
		this.resizeObserver.observe( this.main );
		this.resizeObserver.observe( this.plotCard );
		this.registerDebugFields();
		this.render();
		this.load();
		return this;

	}

	registerDebugFields() {

		const fields = {
			clinician: () => this.report(),
			epg: () => this.epgReport(),
		};
		for ( const [ name, getter ] of Object.entries( fields ) ) this.unregister.push( registerDebug( name, getter ) );

	}

	async load() {

		const query = new URLSearchParams( ( this.window.location.hash.split( '?' )[ 1 ] ) ?? '' );
		try {

			const [ recordings, ...targetLists ] = await Promise.all( [
				fetchJson( '/epg/recordings?limit=1000', { fetchImpl: this.fetchImpl } ),
				...this.sources.map( ( source ) => source.list() ),
			] );
			this.sources.forEach( ( source, k ) => {

				const group = h( 'optgroup', { label: source.title } );
				for ( const target of targetLists[ k ] ) group.append( h( 'option', { value: `${ source.kind }:${ target.id }` }, target.label ) );
				this.targetSelect.append( group );

			} );
			for ( const r of recordings.recordings ) {

				const rate = r.frame_rate_hz ? `, ${ Math.round( r.frame_rate_hz ) } Hz` : '';
				this.recordingSelect.append( h( 'option', { value: String( r.id ) }, `${ r.name } (${ r.n_frames } frames${ rate })` ) );

			}

			this.showStatus( recordings.total || targetLists.some( ( list ) => list.length ) ? '' : 'No recordings or saved poses yet: import a recording or save a pose from the workbench.' );
			if ( query.get( 'target' ) ) {

				this.targetSelect.value = query.get( 'target' );
				await this.chooseTarget( query.get( 'target' ), { keepFrame: true } );

			}

			if ( query.get( 'recording' ) ) {

				this.recordingSelect.value = query.get( 'recording' );
				await this.chooseRecording( query.get( 'recording' ), { keepFrame: true } );

			}

			if ( query.get( 'frame' ) ) this.setFrame( Number( query.get( 'frame' ) ) );
			this.state.loaded = true;

		} catch ( error ) {

			this.fail( error.message );

		}

	}

	async chooseTarget( name, { keepFrame = false } = {} ) {

		this.pause();
		const version = ++ this.loadVersion;
		if ( ! name ) {

			this.state.target = null;

		} else {

			const parsed = parseTargetName( name );
			const source = this.sources.find( ( s ) => s.kind === parsed?.kind );
			if ( ! source ) return this.fail( `There is no target "${ name }"` );
			this.showStatus( 'Computing the target\'s synthetic EPG…' );
			try {

				const target = await source.frames( parsed.id );
				if ( version !== this.loadVersion ) return null;
				this.state.target = { name, ...target, frames: framesFromRows( target.rows ), count: target.rows.length };
				this.state.target.indices = indexTracks( this.state.target.frames, this.state.target.count );
				this.showTarget3d( this.state.target );

			} catch ( error ) {

				return this.fail( error.message );

			}

		}

		return this.compareAndRender( version, keepFrame );

	}

	async chooseRecording( id, { keepFrame = false } = {} ) {

		this.pause();
		const version = ++ this.loadVersion;
		if ( ! id ) {

			this.state.recording = null;

		} else {

			this.showStatus( 'Loading the recording…' );
			try {

				const body = await fetchJson( `/epg/recordings/${ encodeURIComponent( id ) }`, { fetchImpl: this.fetchImpl } );
				if ( version !== this.loadVersion ) return null;
				const frames = framesFromRows( body.frames );
				this.state.recording = { id: body.id, name: body.name, frameRateHz: body.frame_rate_hz, t_s: Float64Array.from( body.t_s ), frames, count: body.n_frames, indices: indexTracks( frames, body.n_frames ) };

			} catch ( error ) {

				return this.fail( error.message );

			}

		}

		return this.compareAndRender( version, keepFrame );

	}

	/** The target's tongue and electrodes in 3D (targets with parameters; one static frame). */
	async showTarget3d( target ) {

		if ( ! target.params ) return;
		try {

			this.palate3d ??= new TargetPalate3D( this.stage3d );
			this.caption3d.textContent = `${ target.label }, palate seen from below`;
			this.state.target3d = await this.palate3d.showParams( target.params );

		} catch ( error ) {

			this.caption3d.textContent = `No 3D view: ${ error.message }`;
			console.warn( `Glasshead: ${ error.message }` );

		}

	}

	/** With both a target and a recording: the compare API's agreement and index differences. */
	async compareAndRender( version, keepFrame ) {

		const { target, recording } = this.state;
		this.state.comparison = null;
		if ( target && recording ) {

			this.showStatus( 'Comparing…' );
			try {

				const reference = { ...target.reference };
				if ( target.count > 1 && target.t_s ) reference.t_s = target.t_s;
				const body = await postJson( `/epg/recordings/${ recording.id }/compare`, { reference }, { fetchImpl: this.fetchImpl } );
				if ( version !== this.loadVersion ) return null;
				this.state.comparison = { ...body, codeFrames: codesFromRows( body.codes ) };

			} catch ( error ) {

				return this.fail( error.message );

			}

		}

		this.hideError();
		this.showStatus( '' );
		if ( ! keepFrame ) this.state.frame = 0;
		this.state.frame = Math.min( this.state.frame, this.frameCount() - 1 );
		this.render();
		return this.state;

	}

	/** Frames of the time base: the recording's, else the target's. */
	frameCount() {

		return Math.max( 1, this.state.recording?.count ?? this.state.target?.count ?? 1 );

	}

	times() {

		return this.state.recording?.t_s ?? ( this.state.target?.t_s ? Float64Array.from( this.state.target.t_s ) : null );

	}

	/** The target frame shown at the current frame. */
	targetFrameIndex() {

		const { target, recording, comparison, frame } = this.state;
		if ( ! target ) return - 1;
		if ( comparison ) return comparison.reference_frame[ frame ];
		if ( recording ) return alignTarget( recording.t_s, target.count, target.t_s )[ frame ];
		return Math.min( frame, target.count - 1 );

	}

	setFrame( frame ) {

		if ( ! Number.isFinite( frame ) ) return;
		this.state.frame = Math.max( 0, Math.min( this.frameCount() - 1, Math.round( frame ) ) );
		this.render();

	}

	step( delta ) {

		this.pause();
		this.setFrame( this.state.frame + delta );

	}

	togglePlay() {

		if ( this.state.playing ) this.pause();
		else this.play();

	}

	/** Play from the current frame at the recording's own frame times (times the speed). */
	play() {

		const times = this.times();
		if ( ! times || times.length < 2 ) return;
		if ( this.state.frame >= times.length - 1 ) this.state.frame = 0;
		this.state.playing = true;
		this.playButton.textContent = 'Pause';
		this.playButton.setAttribute( 'aria-label', 'Pause' );
		const startWall = performance.now();
		const startElapsed = times[ this.state.frame ] - times[ 0 ];
		const tick = ( now ) => {

			if ( ! this.state.playing ) return;
			const elapsed = startElapsed + ( now - startWall ) / 1000 * this.state.speed;
			const frame = frameAtElapsed( times, elapsed );
			if ( frame !== this.state.frame ) this.setFrame( frame );
			if ( elapsed >= times[ times.length - 1 ] - times[ 0 ] ) this.pause();
			else this.raf = this.window.requestAnimationFrame( tick );

		};

		this.raf = this.window.requestAnimationFrame( tick );

	}

	pause() {

		if ( this.raf ) this.window.cancelAnimationFrame( this.raf );
		this.raf = null;
		this.state.playing = false;
		if ( this.playButton ) {

			this.playButton.textContent = 'Play';
			this.playButton.setAttribute( 'aria-label', 'Play' );

		}

	}

	key( event ) {

		const tag = event.target?.tagName;
		if ( tag === 'SELECT' || tag === 'INPUT' || tag === 'TEXTAREA' || event.altKey || event.ctrlKey || event.metaKey ) return;
		const actions = {
			ArrowLeft: () => this.step( - 1 ),
			ArrowRight: () => this.step( 1 ),
			Home: () => this.setFrame( 0 ),
			End: () => this.setFrame( this.frameCount() - 1 ),
			' ': () => this.togglePlay(),
		};
		const action = actions[ event.key ];
		if ( ! action ) return;
		event.preventDefault();
		action();

	}

	fit() {

		this.plot.resize( Math.max( 320, Math.min( 900, this.plotCard.clientWidth - 22 ) ) );
		this.strip.resize( Math.max( 320, Math.min( 1400, this.stripCard.clientWidth - 22 ) ) );
		this.render();

	}

	render() {

		const { target, recording, comparison, frame } = this.state;
		const count = this.frameCount();
		this.slider.max = String( count - 1 );
		this.slider.value = String( frame );
		const times = this.times();
		const ms = times ? Math.round( ( times[ frame ] - times[ 0 ] ) * 1000 ) : 0;
		this.frameLabel.textContent = `Frame ${ frame + 1 } of ${ count }${ times ? ` · ${ ms } ms` : '' }`;

		const t = this.targetFrameIndex();
		this.targetCaption.textContent = target ? target.label : 'none chosen';
		this.targetPalatogram.set( target ? target.frames : null, { offset: Math.max( 0, t ) * EPG_CELLS } );
		this.recordingCaption.textContent = recording ? recording.name : 'none chosen';
		this.recordingPalatogram.set( recording ? recording.frames : null, { offset: frame * EPG_CELLS } );
		if ( comparison ) {

			this.agreementCaption.textContent = `${ Math.round( comparison.agreement[ frame ] * 100 ) }% agree (mean ${ Math.round( comparison.summary.mean_agreement * 100 ) }%)`;
			this.agreementPalatogram.set( null, { codes: comparison.codeFrames, offset: frame * EPG_CELLS } );

		} else {

			this.agreementCaption.textContent = 'choose both';
			this.agreementPalatogram.set( null );

		}

		this.renderTable( t );
		const base = recording ?? ( target ? { t_s: times ?? Float64Array.of( 0, 1 ), count: target.count, frames: target.frames } : null );
		if ( base ) {

			const tracks = [];
			const baseTimes = recording ? recording.t_s : ( target.count > 1 ? times : Float64Array.of( 0, 0.1 ) );
			if ( recording ) tracks.push( { label: `recording ${ recording.name }`, indices: recording.indices, color: TRACK_COLORS.recording } );
			if ( target ) {

				const aligned = recording ? ( comparison ? Int32Array.from( comparison.reference_frame ) : alignTarget( recording.t_s, target.count, target.t_s ) ) : Int32Array.from( baseTimes, ( _, i ) => Math.min( i, target.count - 1 ) );
				const indices = {};
				for ( const [ name, values ] of Object.entries( target.indices ) ) indices[ name ] = Float64Array.from( aligned, ( k ) => values[ k ] );
				tracks.push( { label: `target ${ target.label }`, indices, color: TRACK_COLORS.target, dash: [ 6, 4 ] } );

			}

			this.plot.set( { t_s: baseTimes, tracks, current: recording || target.count > 1 ? frame : null } );
			this.stripCaption.textContent = comparison ? 'Agreement over time (click a frame)' : recording ? 'Recording over time (click a frame)' : 'Target over time';
			if ( recording ) this.strip.set( recording.frames, recording.count, frame, recording.t_s, comparison ? comparison.codeFrames : null );
			else this.strip.set( target.frames, target.count, frame, target.t_s );

		} else {

			this.plot.set( { t_s: [], tracks: [] } );
			this.strip.set( null, 0, 0 );

		}

	}

	renderTable( targetFrame ) {

		const { target, recording, frame, comparison } = this.state;
		const format = ( value ) => ( value === undefined || value === null ? '–' : ( Math.abs( value ) >= 10 ? value.toFixed( 1 ) : value.toFixed( 3 ) ) );
		const rows = [ h( 'tr', {}, h( 'th', {}, 'index' ), h( 'th', {}, 'target' ), h( 'th', {}, 'recording' ), h( 'th', {}, 'difference' ) ) ];
		for ( const name of TABLE_INDICES ) {

			const a = target ? target.indices[ name ][ targetFrame ] : null;
			const b = recording ? recording.indices[ name ][ frame ] : null;
			const d = comparison?.index_difference[ name ]?.[ frame ] ?? ( a !== null && b !== null ? b - a : null );
			rows.push( h( 'tr', {}, h( 'td', {}, name ), h( 'td', {}, format( a ) ), h( 'td', {}, format( b ) ), h( 'td', {}, format( d ) ) ) );

		}

		this.table.replaceChildren( ...rows );

	}

	/** window.glasshead.clinician */
	report() {

		const { target, recording, comparison, frame, playing, loaded, error, speed } = this.state;
		return {
			loaded, error, frame, frames: this.frameCount(), playing, speed,
			target: target ? { name: target.name, label: target.label, frames: target.count, frame: this.targetFrameIndex() } : null,
			recording: recording ? { id: recording.id, name: recording.name, frames: recording.count, frameRateHz: recording.frameRateHz } : null,
			agreement: comparison ? comparison.agreement[ frame ] : null,
			target3d: this.state.target3d ? { rows: this.state.target3d.rows, contacted: this.state.target3d.contacted, squares: this.palate3d?.electrodes?.contacted ?? null } : null,
			meanAgreement: comparison ? comparison.summary.mean_agreement : null,
		};

	}

	/** window.glasshead.epg in this view: the contacts of the frame shown, real and synthetic. */
	epgReport() {

		const { target, recording, frame } = this.state;
		const side = ( frames, index ) => {

			if ( ! frames || index < 0 ) return null;
			const cells = frames.subarray( index * EPG_CELLS, ( index + 1 ) * EPG_CELLS );
			const contacted = cells.reduce( ( sum, v ) => sum + v, 0 );
			return { rows: contactRows( GRID, cells ), contacted, percent: Math.round( 100000 * contacted / 62 ) / 1000 };

		};

		const real = side( recording?.frames, frame );
		const synthetic = side( target?.frames, this.targetFrameIndex() );
		const shown = real ?? synthetic;
		return { source: 'clinician', frame, rows: shown?.rows ?? null, contacted: shown?.contacted ?? 0, percent: shown?.percent ?? 0, recording: real, synthetic };

	}

	showStatus( text ) {

		this.status.textContent = text;

	}

	fail( message ) {

		this.state.error = message;
		this.error.textContent = message;
		this.error.hidden = false;
		this.showStatus( '' );
		console.error( `Glasshead: ${ message }` );
		return null;

	}

	hideError() {

		this.state.error = null;
		this.error.hidden = true;

	}

	unmount() {

		this.pause();
		this.loadVersion ++;
		this.window.removeEventListener( 'keydown', this.onKey );
		this.resizeObserver?.disconnect();
		this.palate3d?.dispose();
		for ( const unregister of this.unregister ) unregister();
		this.root.remove();

	}

}

/** Route entry for the view registry. */
export function mountClinicianView( container ) {

	return new ClinicianView().mount( container );

}
